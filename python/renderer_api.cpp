// ssgi.Renderer's bindings: its methods and properties as Python sees them, and what it reports
// of the frame (profile, memory).
#include "renderer_object.h"

#include <pybind11/stl.h>

namespace ssgi::python {

py::dict RendererObject::profile() const {
    open();
    FrameProfile p;
    locked([&] { p = renderer_->lastFrameProfile(); });
    py::dict passes, invocations;
    for (const PassTiming& pass : p.passes)
        if (pass.ran) {
            passes[py::str(pass.name)] = pass.milliseconds;
            invocations[py::str(pass.name)] = pass.invocations;
        }
    py::dict d;
    d["passes"] = passes;
    d["invocations"] = invocations;
    d["sum_ms"] = p.passSumMs();
    d["host_ms"] = p.hostMs;
    return d;
}

py::dict RendererObject::memory() const {
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

void defineRenderer(py::module_& m) {
    using R = RendererObject;
    py::class_<R>(m, "Renderer",
                  "The real-time renderer of a scene at a size, on a Vulkan device (a substring of "
                  "its name; None: SSGI_DEVICE, else the first). A change of the scene's settings "
                  "(here or through the scene) applies at the next render(), restarting every "
                  "cache; set_camera, set_light and set_time apply at the next frame, restarting "
                  "what they invalidate. close() (or a with block) gives its device memory back.")
        .def(py::init<const std::shared_ptr<SceneObject>&, const SizeArg&,
                      const std::optional<std::string>&, const std::string&, const NamesArg&>(),
             py::arg("scene"), py::arg("size") = py::make_tuple(512, 512),
             py::arg("device") = py::none(), py::arg("view") = "final",
             py::arg("keep") = py::list(),
             "A renderer of `scene` at `size` (width, height: NumPy's shape is (height, width)) "
             "showing `view` (view_names()); `keep` names images of the frame that read() must "
             "find whole (an effect's raw output, such as 'ao'; '*' keeps all).")
        .def("render", &R::render, py::arg("frames") = 1, py::arg("view") = py::none(),
             "Renders `frames` frames and returns the last one's linear image (the view's linear "
             "quantity for a debug view) as an ssgi.Image of float32, height x width x 3. A "
             "change of the scene's settings since the last frame rebuilds the renderer first "
             "(its frames are then those of a new Renderer). `view` switches the view from now "
             "on (None: the renderer's). Ctrl-C stops it between frames (KeyboardInterrupt); the "
             "renderer stays usable.")
        .def("read", &R::read, py::arg("name"),
             "An image of the last frame by name (one of images(): 'ldr', 'gbuffer.normal', ...) "
             "as float32 RGBA, height x width x 4; an image of integers (the world cache's keys, "
             "lists and voxels) as its integers, uint32 or uint8, height x width.")
        .def("images", &R::images, "The names read() accepts in this renderer's frame.")
        .def("set_time", &R::setTime, py::arg("seconds"),
             "Moves the camera along the scene's camera path and its objects along theirs, as "
             "render --time does.")
        .def("set_camera", &R::setCamera, py::arg("position") = py::none(),
             py::arg("target") = py::none(), py::arg("up") = py::none(),
             py::arg("fov") = py::none(),
             "Places the camera (world coordinates; fov vertical, in degrees); what is not given "
             "stays: a new position alone keeps looking at the camera's target.")
        .def_property_readonly("camera", &R::camera,
                               "The camera as a dict: position, target (the point it looks at: "
                               "the target set last, else the point of its view nearest the "
                               "scene's centre), forward, up and fov (degrees).")
        .def("set_light", &R::setLight, py::arg("position") = py::none(),
             py::arg("direction") = py::none(), py::arg("target") = py::none(),
             py::arg("color") = py::none(), py::arg("intensity") = py::none(),
             py::arg("cone") = py::none(), py::arg("inner_cone") = py::none(),
             py::arg("radius") = py::none(),
             "Changes the spot light from the next frame on, checked as a scene file's 'light' "
             "is (cone angles in degrees); what is not given stays. The caches that depend on "
             "the light start over.")
        .def_property_readonly("light", &R::light,
                               "The light as a dict: position, direction, color, intensity, "
                               "cone, inner_cone (degrees) and radius.")
        .def_property(
            "settings", [](const R& r) { return settingsOf(r.scene()); },
            [](R& r, const SettingsArg& values) { setSettings(r.scene(), values.value); },
            "The settings of the renderer's scene (its scene.settings): a change applies at the "
            "next render(), which rebuilds the renderer from the changed scene.")
        .def_property_readonly(
            "scene", [](const R& r) { return r.scene(); }, "The scene the renderer renders.")
        .def("cut", &R::cut, "Starts every cached history afresh at the next frame.")
        .def("profile", &R::profile,
             "The last frame's {'passes': {name: ms}, 'invocations': {name: compute invocations\n"
             "dispatched}, 'sum_ms', 'host_ms'} (docs/profiling.md).")
        .def("memory", &R::memory,
             "What the frame graph holds: 'images' by name in bytes, 'shared_bytes', "
             "'shared_images', 'held_bytes'.")
        .def("close", &R::close,
             "Gives the renderer's device memory back; any later call but close() raises "
             "ssgi.InputError (a ValueError).")
        .def(
            "__enter__", [](R& r) -> R& { return r; }, py::return_value_policy::reference,
            "The renderer itself.")
        .def(
            "__exit__",
            [](R& r, const py::object&, const py::object&, const py::object&) {
                r.close();
                return false;
            },
            py::arg("type"), py::arg("value"), py::arg("traceback"), "Closes the renderer.")
        .def("__repr__", &R::repr, "The scene, the size, the view and the device.")
        .def_property_readonly("size", &R::size, "(width, height) of the images.")
        .def_property_readonly("view", &R::view, "The view render() shows.")
        .def_property_readonly("cuts", &R::cuts, "Cuts so far, requested or automatic.")
        .def_property_readonly("rebuilds", &R::rebuilds,
                               "Times a change of the scene rebuilt the renderer.")
        .def_property_readonly("frames", &R::frames,
                               "Frames rendered so far (read from another thread too).")
        .def_property_readonly("closed", &R::closed, "Whether close() was called.")
        .def_property_readonly("device", &R::device, "The device's name and driver.")
        .def_property_readonly("validation", &R::validation, "Whether the validation layer is on.");
}

} // namespace ssgi::python
