// The Vulkan devices the module's renderers share: one context per device for the whole process.
#pragma once

#include "module.h"

#include "vk/context.h"

#include <memory>
#include <mutex>
#include <string>

namespace ssgi::python {

// One Vulkan context per device, as the tests keep one: creating an instance is slow under the
// validation layer. Its queue and command pool take one frame at a time, so every use holds
// `mutex`.
struct Device {
    std::unique_ptr<vk::Context> ctx;
    std::mutex mutex;
    ~Device();
};

// The device as the programs pick it: `name` (a substring of the device's name), else
// SSGI_DEVICE, else the first; the validation layer with SSGI_VALIDATION=1 or in a debug build.
// InputError for a name no device has (a bad value, as --device's).
std::shared_ptr<Device> deviceNamed(const std::string& name);

// view_names(), validation_messages() and the atexit hook that closes the devices.
void defineDevices(py::module_& m);

} // namespace ssgi::python
