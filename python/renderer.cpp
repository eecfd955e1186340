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

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>

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
    if (!py::isinstance<py::str>(value)) {
        try {
            t = py::tuple(py::reinterpret_borrow<py::object>(value));
        } catch (const py::error_already_set&) {
        }
    }
    if (!t || t.size() != 3)
        throw InputError(name + ": expected three numbers (x, y, z), got " +
                         std::string(py::repr(value)));
    glm::vec3 v;
    for (int i = 0; i < 3; ++i)
        v[i] = float(numberArg(name, t[size_t(i)], -1e10, 1e10));
    return v;
}

py::list vec3List(glm::vec3 v) {
    return py::cast(std::vector<float>{v.x, v.y, v.z});
}

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names)
        text += (text.empty() ? "" : ", ") + name;
    return text;
}

std::vector<std::string> namesOf(const py::handle& keep) {
    if (py::isinstance<py::str>(keep))
        throw py::type_error("keep: expected a list of image names, got a str (keep=[" +
                             std::string(py::repr(keep)) + "] names one)");
    std::vector<std::string> names;
    for (const py::handle name : keep) {
        if (!py::isinstance<py::str>(name))
            throw py::type_error("keep: an image's name is a str, not " + typeName(name));
        names.push_back(name.cast<std::string>());
    }
    return names;
}

class RendererObject {
public:
    RendererObject(const std::shared_ptr<SceneObject>& scene, const SizeArg& size,
                   const std::optional<std::string>& device, const std::string& view,
                   const NamesArg& keep)
        : scene_(sceneArg(scene).scene), sceneName_(scene->path), camera_(scene_->camera) {
        RenderOptions options;
        // render's range (--size); the renderer refuses 0 and what the device cannot hold.
        sizeArg(size.value, options.width, options.height, 0, 1000000);
        options.view = view;
        options.keep = namesOf(keep.value);
        device_ = deviceNamed(device.value_or(""));
        {
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(device_->mutex);
            renderer_ = std::make_unique<Renderer>(*device_->ctx, *scene_, options);
        }
        raiseWarnings();
        view_ = view;
        // The renderer passes over names its frame lacks; a name a user gave is checked here.
        for (const std::string& name : options.keep)
            if (name != "*" && !renderer_->hasImage(name)) {
                const std::string names = joined(imageNames(true));
                close();
                throw InputError("keep: no image named '" + name + "' in this frame; the " +
                                 "images it can keep: " + names);
            }
    }
    ~RendererObject() { close(); }

    void close() {
        if (!renderer_) return;
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(device_->mutex);
        renderer_.reset();
    }

    py::array render(const IntArg& frames, const std::optional<std::string>& view) {
        open();
        const uint32_t count = countArg("frames", frames.value, 1, 1000000);
        std::vector<float> hdr;
        std::optional<py::error_already_set> interrupt;
        {
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(device_->mutex);
            if (view && *view != view_) {
                renderer_->setView(*view);
                view_ = *view;
            }
            for (uint32_t f = 0; f < count; ++f) {
                renderer_->renderFrame(camera_);
                ++frames_;
                if (f + 1 == count) break;
                // A signal (Ctrl-C) stops the call between frames; the frames done stay done.
                py::gil_scoped_acquire acquire;
                if (PyErr_CheckSignals() != 0) {
                    interrupt.emplace();
                    break;
                }
            }
            if (!interrupt) hdr = renderer_->readImage("hdr");
        }
        if (interrupt) throw *interrupt;
        raiseWarnings();
        const VkExtent2D size = renderer_->size();
        return rgbArray(std::move(hdr), size.width, size.height);
    }

    // The names read() accepts in this renderer's frame.
    std::vector<std::string> images() const {
        open();
        return imageNames(false);
    }

    py::array read(const std::string& name) {
        open();
        if (frames_ == 0) throw InputError(name + ": no frame rendered yet; call render() first");
        const std::vector<std::string> names = images();
        if (std::find(names.begin(), names.end(), name) == names.end()) {
            if (renderer_->hasImage(name) && overwritten(name))
                throw InputError("read: '" + name + "' shares its memory with other images of " +
                                 "the frame, which overwrite it; name it in keep= when making " +
                                 "the renderer (Renderer(scene, keep=['" + name +
                                 "'])) to read it");
            throw InputError("read: no image named '" + name +
                             "' in this frame; it has: " + joined(names));
        }
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

    void setTime(const FloatArg& seconds) {
        open();
        const float t = float(numberArg("time", seconds.value, 0.0, 1e9));
        camera_ = cameraAtTime(*scene_, t, sceneName_);
        locked([&] { renderer_->setTime(t); });
    }

    void setCamera(const std::optional<Vec3Arg>& position, const std::optional<Vec3Arg>& target,
                   const std::optional<Vec3Arg>& up, const std::optional<FloatArg>& fov) {
        open();
        Camera camera = camera_;
        if (position) camera.position = vec3Arg("position", position->value);
        if (target || up) {
            const glm::vec3 forward = camera_.orientation * glm::vec3(0, 0, -1);
            const glm::vec3 to =
                target ? vec3Arg("target", target->value) : camera.position + forward;
            const glm::vec3 upward =
                up ? vec3Arg("up", up->value) : camera_.orientation * glm::vec3(0, 1, 0);
            if (!(glm::length(to - camera.position) > 0.0f))
                throw InputError("target: the camera's position, so no direction to look in");
            if (!(glm::length(upward) > 0.0f)) throw InputError("up: a zero vector");
            camera.orientation = lookRotation(to - camera.position, upward);
        }
        if (fov)
            camera.yfov = glm::radians(float(numberArg("fov", fov->value, kMinFovDegrees, 179.0)));
        camera_ = camera;
    }

    py::dict camera() const {
        py::dict d;
        const glm::vec3 forward = camera_.orientation * glm::vec3(0, 0, -1);
        d["position"] = vec3List(camera_.position);
        // What set_camera takes: a point looked at (one unit ahead), the up vector and fov.
        d["target"] = vec3List(camera_.position + forward);
        d["forward"] = vec3List(forward);
        d["up"] = vec3List(camera_.orientation * glm::vec3(0, 1, 0));
        d["fov"] = glm::degrees(camera_.yfov);
        return d;
    }

    void cut() {
        open();
        locked([&] { renderer_->cut(); });
    }

    py::dict profile() const {
        open();
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
        open();
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
        open();
        return py::make_tuple(renderer_->size().width, renderer_->size().height);
    }
    const std::string& view() const { return view_; }
    uint32_t cuts() const {
        open();
        return renderer_->cuts();
    }
    uint64_t frames() const { return frames_; }
    bool closed() const { return !renderer_; }
    std::string device() const {
        return std::string(device_->ctx->properties.deviceName) + " (" + device_->ctx->driverName +
               ")";
    }
    bool validation() const { return device_->ctx->validationEnabled; }
    std::string repr() const {
        std::string text = "<ssgi.Renderer of " + std::string(py::repr(py::str(sceneName_)));
        if (!renderer_) return text + ", closed>";
        const VkExtent2D size = renderer_->size();
        return text + " at " + std::to_string(size.width) + "x" + std::to_string(size.height) +
               ", view " + std::string(py::repr(py::str(view_))) + ", on " +
               std::string(py::repr(py::str(device()))) + ", " + std::to_string(frames_) +
               " frames>";
    }

private:
    // The names read() finds in the frame: its graph's images, the cached effects' histories,
    // and the position the G-buffer's depth gives; with `withOverwritten`, also the transient
    // images a later pass overwrites, which keep= can name.
    std::vector<std::string> imageNames(bool withOverwritten) const {
        std::vector<std::string> names{"gbuffer.position"};
        for (const auto& image : renderer_->frameGraph().imageMemory())
            if (image.historyPair.empty()) names.push_back(image.name);
        for (const std::string& effect : renderer_->cachedEffects())
            for (const char* part : {".history", ".count", ".meta"})
                names.push_back(effect + part);
        if (std::find(names.begin(), names.end(), "gbuffer.view_depth") == names.end() &&
            renderer_->hasImage("gbuffer.view_depth"))
            names.push_back("gbuffer.view_depth");
        std::vector<std::string> readable;
        for (const std::string& name : names)
            if (renderer_->hasImage(name) && (withOverwritten || !overwritten(name)) &&
                std::find(readable.begin(), readable.end(), name) == readable.end())
                readable.push_back(name);
        std::sort(readable.begin(), readable.end());
        return readable;
    }

    // A transient image whose memory a later pass of the frame wrote (not named in keep=).
    bool overwritten(const std::string& name) const {
        const graph::ImageRef ref = renderer_->frameGraph().find(name);
        return ref.valid() && !renderer_->frameGraph().readable(ref);
    }
    void open() const {
        if (!renderer_) throw InputError("this renderer is closed");
    }
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
    // Frames rendered so far; read by another thread while render() runs.
    std::atomic<uint64_t> frames_{0};
};

} // namespace

void defineRenderer(py::module_& m) {
    py::class_<RendererObject>(m, "Renderer",
                               "The real-time renderer of a scene at a size, on a Vulkan device "
                               "(a substring of its name; None: SSGI_DEVICE, else the first). It "
                               "renders the scene as it was when the renderer was made, at "
                               "`size`, in `view`, until changed; close() (or a with block) "
                               "gives its device memory back.")
        .def(py::init<const std::shared_ptr<SceneObject>&, const SizeArg&,
                      const std::optional<std::string>&, const std::string&, const NamesArg&>(),
             py::arg("scene"), py::arg("size") = py::make_tuple(512, 512),
             py::arg("device") = py::none(), py::arg("view") = "final",
             py::arg("keep") = py::list(),
             "A renderer of `scene` at `size` (width, height) showing `view` (view_names()); "
             "`keep` names images of the frame that read() must find whole (an effect's raw "
             "output, such as 'ao'; '*' keeps all).")
        .def("render", &RendererObject::render, py::arg("frames") = 1, py::arg("view") = py::none(),
             "Renders `frames` frames and returns the last one's linear image (the view's linear "
             "quantity for a debug view) as float32, height x width x 3. `view` switches the view "
             "from now on (None: the renderer's). Ctrl-C stops it between frames "
             "(KeyboardInterrupt); the renderer stays usable.")
        .def("read", &RendererObject::read, py::arg("name"),
             "An image of the last frame by name (one of images(): 'ldr', 'gbuffer.normal', ...) "
             "as float32 RGBA, height x width x 4.")
        .def("images", &RendererObject::images,
             "The names read() accepts in this renderer's frame.")
        .def("set_time", &RendererObject::setTime, py::arg("seconds"),
             "Moves the camera along the scene's camera path and its objects along theirs, as "
             "render --time does.")
        .def("set_camera", &RendererObject::setCamera, py::arg("position") = py::none(),
             py::arg("target") = py::none(), py::arg("up") = py::none(),
             py::arg("fov") = py::none(),
             "Places the camera (world coordinates; fov vertical, in degrees); what is not given "
             "stays.")
        .def_property_readonly("camera", &RendererObject::camera,
                               "The camera as a dict: position, target (a point one unit "
                               "ahead, as set_camera takes it), forward, up and fov (degrees).")
        .def("cut", &RendererObject::cut, "Starts every cached history afresh at the next frame.")
        .def("profile", &RendererObject::profile,
             "The last frame's {'passes': {name: ms}, 'sum_ms', 'host_ms'} (docs/profiling.md).")
        .def("memory", &RendererObject::memory,
             "What the frame graph holds: 'images' by name in bytes, 'shared_bytes', "
             "'shared_images', 'held_bytes'.")
        .def("close", &RendererObject::close,
             "Gives the renderer's device memory back; any later call but close() raises "
             "ValueError.")
        .def(
            "__enter__", [](RendererObject& r) -> RendererObject& { return r; },
            py::return_value_policy::reference, "The renderer itself.")
        .def(
            "__exit__",
            [](RendererObject& r, const py::object&, const py::object&, const py::object&) {
                r.close();
                return false;
            },
            py::arg("type"), py::arg("value"), py::arg("traceback"), "Closes the renderer.")
        .def("__repr__", &RendererObject::repr, "The scene, the size, the view and the device.")
        .def_property_readonly("size", &RendererObject::size, "(width, height) of the images.")
        .def_property_readonly("view", &RendererObject::view, "The view render() shows.")
        .def_property_readonly("cuts", &RendererObject::cuts,
                               "Cuts so far, requested or automatic.")
        .def_property_readonly("frames", &RendererObject::frames,
                               "Frames rendered so far (read from another thread too).")
        .def_property_readonly("closed", &RendererObject::closed, "Whether close() was called.")
        .def_property_readonly("device", &RendererObject::device, "The device's name and driver.")
        .def_property_readonly("validation", &RendererObject::validation,
                               "Whether the validation layer is on.");

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
