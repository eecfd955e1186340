// ssgi.Renderer: the real-time renderer on a Vulkan device, driven as the render program drives
// it (the same options, the same frames, the image read back once), with the GIL released while
// the device works.
#include "module.h"

#include "app/cli.h"
#include "renderer.h"
#include "scene/animation.h"
#include "scene/camera.h"
#include "scene/gltf_internal.h"
#include "vk/context.h"

#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <map>
#include <mutex>

namespace ssgi::python {

namespace {

std::atomic<uint32_t> retiredMessages{0}; // of devices already closed

// One Vulkan context per device for the whole process, as the tests keep one: creating an
// instance is slow under the validation layer. Its queue and command pool take one frame at a
// time, so every use holds `mutex`.
struct Device {
    std::unique_ptr<vk::Context> ctx;
    std::mutex mutex;
    ~Device() {
        if (ctx) retiredMessages += ctx->validationMessageCount();
    }
};

std::mutex registryMutex;
// Never destroyed with the other statics: the module's atexit hook empties it while the driver
// is still there, and renderers still alive then keep their own device.
std::map<std::string, std::shared_ptr<Device>>& registry() {
    static auto* devices = new std::map<std::string, std::shared_ptr<Device>>();
    return *devices;
}

// The device as the programs pick it: `name` (a substring of the device's name), else
// SSGI_DEVICE, else the first; the validation layer with SSGI_VALIDATION=1 or in a debug build.
std::shared_ptr<Device> deviceNamed(const std::string& name) {
    cli::CommonArgs args;
    args.scene = "-"; // no default scene to look for
    args.device = name;
    cli::finishCommonArgs(args);
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(registryMutex);
    const std::string key = args.device + (args.validation ? "+v" : "");
    if (const auto found = registry().find(key); found != registry().end()) return found->second;
    // Kept only once open: a device that fails to open (no such name) leaves nothing behind.
    auto device = std::make_shared<Device>();
    device->ctx = std::make_unique<vk::Context>(vk::ContextOptions{args.validation, args.device});
    registry()[key] = device;
    return device;
}

glm::vec3 vec3Arg(const std::string& name, const py::handle& value) {
    py::tuple t;
    try {
        t = py::tuple(py::reinterpret_borrow<py::object>(value));
    } catch (const py::error_already_set&) {
    }
    if (!t || t.size() != 3) throw InputError(name + ": expected three numbers (x, y, z)");
    glm::vec3 v;
    for (int i = 0; i < 3; ++i)
        v[i] = float(numberArg(name, t[size_t(i)], -1e10, 1e10));
    return v;
}

py::list vec3List(glm::vec3 v) {
    return py::cast(std::vector<float>{v.x, v.y, v.z});
}

class RendererObject {
public:
    RendererObject(const std::shared_ptr<SceneObject>& scene, const py::object& size,
                   const py::object& device, const std::string& view,
                   const std::vector<std::string>& keep)
        : scene_(scene->scene), sceneName_(scene->path), camera_(scene_->camera) {
        RenderOptions options;
        // render's range (--size); the renderer refuses 0 and what the device cannot hold.
        sizeArg(size, options.width, options.height, 0, 1000000);
        options.view = view;
        options.keep = keep;
        device_ = deviceNamed(device.is_none() ? "" : py::str(device).cast<std::string>());
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(device_->mutex);
        renderer_ = std::make_unique<Renderer>(*device_->ctx, *scene_, options);
        view_ = view;
    }
    ~RendererObject() {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(device_->mutex);
        renderer_.reset();
    }

    py::array render(const py::handle& frames, const std::string& view) {
        const uint32_t count = countArg("frames", frames, 1, 1000000);
        std::vector<float> hdr;
        {
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(device_->mutex);
            if (view != view_) renderer_->setView(view);
            view_ = view;
            for (uint32_t f = 0; f < count; ++f)
                renderer_->renderFrame(camera_);
            hdr = renderer_->readImage("hdr");
            frames_ += count;
        }
        const VkExtent2D size = renderer_->size();
        return rgbArray(std::move(hdr), size.width, size.height);
    }

    py::array read(const std::string& name) {
        if (frames_ == 0) throw InputError(name + ": no frame rendered yet");
        if (!renderer_->hasImage(name))
            throw InputError(name + ": this frame has no such image (an effect's raw output must "
                                    "be named in keep=)");
        std::vector<float> rgba;
        VkExtent2D size = renderer_->size();
        {
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(device_->mutex);
            rgba = renderer_->readImage(name);
        }
        // A screen image is read at the output's size; another (the RSM's) at its own.
        if (rgba.size() != size_t(size.width) * size.height * 4) {
            const graph::ImageRef ref = renderer_->frameGraph().find(name);
            size = renderer_->frameGraph().image(ref).extent;
        }
        if (rgba.size() != size_t(size.width) * size.height * 4)
            throw std::runtime_error(name + ": read back an image of an unexpected size");
        return rgbaArray(std::move(rgba), size.width, size.height);
    }

    void setTime(const py::handle& seconds) {
        const float t = float(numberArg("time", seconds, 0.0, 1e9));
        camera_ = cameraAtTime(*scene_, t, sceneName_);
        locked([&] { renderer_->setTime(t); });
    }

    void setCamera(const py::object& position, const py::object& target, const py::object& up,
                   const py::object& fov) {
        Camera camera = camera_;
        if (!position.is_none()) camera.position = vec3Arg("position", position);
        if (!target.is_none() || !up.is_none()) {
            const glm::vec3 forward = camera_.orientation * glm::vec3(0, 0, -1);
            const glm::vec3 to =
                target.is_none() ? camera.position + forward : vec3Arg("target", target);
            const glm::vec3 upward =
                up.is_none() ? camera_.orientation * glm::vec3(0, 1, 0) : vec3Arg("up", up);
            if (!(glm::length(to - camera.position) > 0.0f))
                throw InputError("target: the camera's position, so no direction to look in");
            if (!(glm::length(upward) > 0.0f)) throw InputError("up: a zero vector");
            camera.orientation = lookRotation(to - camera.position, upward);
        }
        if (!fov.is_none())
            camera.yfov = glm::radians(float(numberArg("fov", fov, kMinFovDegrees, 179.0)));
        camera_ = camera;
    }

    py::dict camera() const {
        py::dict d;
        d["position"] = vec3List(camera_.position);
        d["forward"] = vec3List(camera_.orientation * glm::vec3(0, 0, -1));
        d["up"] = vec3List(camera_.orientation * glm::vec3(0, 1, 0));
        d["fov"] = glm::degrees(camera_.yfov);
        return d;
    }

    void cut() {
        locked([&] { renderer_->cut(); });
    }

    py::dict profile() const {
        FrameProfile p;
        locked([&] { p = renderer_->lastFrameProfile(); });
        py::dict passes;
        for (const PassTiming& pass : p.passes)
            if (pass.ran) passes[py::str(pass.name)] = pass.milliseconds;
        py::dict d;
        d["passes"] = passes;
        d["sum_ms"] = p.passSumMs();
        d["host_ms"] = p.hostMs;
        return d;
    }

    py::dict memory() const {
        std::vector<graph::FrameGraph::HeldImage> imageMemory;
        graph::FrameGraph::SharedMemory shared;
        VkDeviceSize held = 0;
        locked([&] {
            const graph::FrameGraph& graph = renderer_->frameGraph();
            imageMemory = graph.imageMemory();
            shared = graph.sharedMemory();
            held = graph.heldMemory();
        });
        py::dict images;
        for (const graph::FrameGraph::HeldImage& image : imageMemory)
            images[py::str(image.name)] = image.bytes;
        py::dict d;
        d["images"] = images;
        d["shared_bytes"] = shared.bytes;
        d["shared_images"] = shared.images;
        d["held_bytes"] = held;
        return d;
    }

    py::tuple size() const {
        return py::make_tuple(renderer_->size().width, renderer_->size().height);
    }
    const std::string& view() const { return view_; }
    uint32_t cuts() const { return renderer_->cuts(); }
    std::string device() const {
        return std::string(device_->ctx->properties.deviceName) + " (" + device_->ctx->driverName +
               ")";
    }
    bool validation() const { return device_->ctx->validationEnabled; }

private:
    // Runs `f` on the renderer with the GIL released and the device held (another thread may be
    // rendering on it).
    template <class F> void locked(F&& f) const {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(device_->mutex);
        f();
    }

    std::shared_ptr<Device> device_;
    std::shared_ptr<const Scene> scene_; // the scene as it was when the renderer was made
    std::string sceneName_;
    std::unique_ptr<Renderer> renderer_;
    Camera camera_;
    std::string view_;
    uint32_t frames_ = 0;
};

} // namespace

void defineRenderer(py::module_& m) {
    py::class_<RendererObject>(m, "Renderer",
                               "The real-time renderer of a scene at a size, on a Vulkan device "
                               "(a substring of its name; None: SSGI_DEVICE, else the first).")
        .def(py::init<const std::shared_ptr<SceneObject>&, const py::object&, const py::object&,
                      const std::string&, const std::vector<std::string>&>(),
             py::arg("scene"), py::arg("size") = py::make_tuple(512, 512),
             py::arg("device") = py::none(), py::arg("view") = "final",
             py::arg("keep") = std::vector<std::string>())
        .def("render", &RendererObject::render, py::arg("frames") = 1, py::arg("view") = "final",
             "Renders `frames` frames and returns the last one's linear image (the view's linear "
             "quantity for a debug view) as float32, height x width x 3.")
        .def("read", &RendererObject::read, py::arg("name"),
             "An image of the last frame by name (\"gbuffer.normal\", \"ldr\", ...) as float32 "
             "RGBA, height x width x 4.")
        .def("set_time", &RendererObject::setTime, py::arg("seconds"))
        .def("set_camera", &RendererObject::setCamera, py::arg("position") = py::none(),
             py::arg("target") = py::none(), py::arg("up") = py::none(),
             py::arg("fov") = py::none())
        .def_property_readonly("camera", &RendererObject::camera)
        .def("cut", &RendererObject::cut)
        .def("profile", &RendererObject::profile)
        .def("memory", &RendererObject::memory)
        .def_property_readonly("size", &RendererObject::size)
        .def_property_readonly("view", &RendererObject::view)
        .def_property_readonly("cuts", &RendererObject::cuts)
        .def_property_readonly("device", &RendererObject::device)
        .def_property_readonly("validation", &RendererObject::validation);

    m.def("view_names", [] { return viewNames(); });
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
