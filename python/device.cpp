// The devices of the module's renderers, opened once per process and closed at exit.
#include "device.h"

#include "app/cli.h"
#include "renderer.h"

#include <pybind11/stl.h>

#include <atomic>
#include <map>

namespace ssgi::python {

namespace {

std::atomic<uint32_t> retiredMessages{0}; // of devices already closed

std::mutex registryMutex;
// Never destroyed with the other statics: the module's atexit hook empties it while the driver
// is still there, and renderers still alive then keep their own device.
std::map<std::string, std::shared_ptr<Device>>& registry() {
    static auto* devices = new std::map<std::string, std::shared_ptr<Device>>();
    return *devices;
}

} // namespace

Device::~Device() {
    if (ctx) retiredMessages += ctx->validationMessageCount();
}

std::shared_ptr<Device> deviceNamed(const std::string& name) {
    cli::CommonArgs args;
    args.device = name;
    cli::finishDeviceArgs(args); // no scene to look for
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(registryMutex);
    const std::string key = args.device + (args.validation ? "+v" : "");
    if (const auto found = registry().find(key); found != registry().end()) return found->second;
    // Kept only once open: a device that fails to open (no such name) leaves nothing behind.
    auto device = std::make_shared<Device>();
    try {
        device->ctx =
            std::make_unique<vk::Context>(vk::ContextOptions{args.validation, args.device});
    } catch (const vk::VulkanError& e) {
        // A name no device has is a bad value, as docs/python.md says; a device that is there
        // and fails is the device's failure.
        const std::string named = "no usable Vulkan device named '";
        if (!args.device.empty() && std::string(e.what()).rfind(named, 0) == 0)
            throw InputError(e.what());
        throw;
    }
    registry()[key] = device;
    return device;
}

void defineDevices(py::module_& m) {
    m.def(
        "view_names", [] { return viewNames(); },
        "The views a renderer can show ('final' and the debug views).");
    m.def(
        "validation_messages",
        [] {
            uint32_t count = retiredMessages;
            std::lock_guard<std::mutex> lock(registryMutex);
            for (const auto& [name, device] : registry())
                count += device->ctx->validationMessageCount();
            return count;
        },
        "Messages the validation layer has reported so far on every device (tests require 0).");
    m.def("_release_devices", [] {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(registryMutex);
        registry().clear();
    });
}

} // namespace ssgi::python
