// ssgi.Renderer: the real-time renderer on a Vulkan device, driven as the render program drives
// it (the same options, the same frames, the image read back once), with the GIL released while
// the device works. A change of the scene's settings rebuilds it at the next frame, as the
// viewer's panel does (a new renderer from the changed scene: every cache starts over, and the
// frames are those of a renderer made anew, bit for bit), taking the old one's scene on the
// device and its pipelines where only settings changed, so a change compiles only the shaders
// it specializes otherwise; the camera, the light, the time and the view carry over. The light and
// the camera change without a rebuild: the renderer restarts what they invalidate
// (Renderer::setLight, its cut detection: renderer_camera_light.cpp).
#include "renderer_object.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <cstring>

namespace ssgi::python {

namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names)
        text += (text.empty() ? "" : ", ") + name;
    return text;
}

std::vector<std::string> namesOf(const py::handle& keep) {
    if (py::isinstance<py::str>(keep))
        throw ArgumentTypeError("keep: expected a list of image names, got a str (keep=[" +
                                std::string(py::repr(keep)) + "] names one)");
    std::vector<std::string> names;
    for (const py::handle name : keep) {
        if (!py::isinstance<py::str>(name))
            throw ArgumentTypeError("keep: an image's name is a str, not " + typeName(name));
        names.push_back(name.cast<std::string>());
    }
    return names;
}

// An integer image's texels, which Renderer::readImage hands over as floats: R32_UINT's bits
// (keys, masks, counts), R8_UINT's values; as NumPy integers, height x width.
template <class T>
py::array integerArray(const std::vector<float>& rgba, uint32_t width, uint32_t height, bool bits) {
    py::array_t<T> out({py::ssize_t(height), py::ssize_t(width)});
    T* data = out.mutable_data();
    for (size_t i = 0; i < size_t(width) * height; ++i) {
        if (bits) {
            uint32_t word = 0;
            std::memcpy(&word, &rgba[4 * i], sizeof(word));
            data[i] = T(word);
        } else {
            data[i] = T(rgba[4 * i]);
        }
    }
    return out;
}

} // namespace

RendererObject::RendererObject(const std::shared_ptr<SceneObject>& scene, const SizeArg& size,
                               const std::optional<std::string>& device, const std::string& view,
                               const NamesArg& keep)
    : sceneObject_(scene), scene_(sceneArg(scene).scene), camera_(scene_->camera),
      light_(scene_->light) {
    // render's range (--size); the renderer refuses 0 and what the device cannot hold.
    sizeArg(size.value, options_.width, options_.height, 0, 1000000);
    options_.view = view;
    options_.keep = namesOf(keep.value);
    device_ = deviceNamed(device.value_or(""));
    renderer_ = build(*scene_);
    loads_ = sceneObject_->loads;
    view_ = view;
    // The renderer passes over names its frame lacks; a name a user gave is checked here.
    for (const std::string& name : options_.keep)
        if (name != "*" && !renderer_->hasImage(name)) {
            const std::string names = joined(imageNames(true));
            close();
            throw InputError("keep: no image named '" + name + "' in this frame; the " +
                             "images it can keep: " + names);
        }
}

std::unique_ptr<Renderer> RendererObject::build(const Scene& scene, Renderer* previous) {
    std::unique_ptr<Renderer> made;
    {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(device_->mutex);
        made = previous ? std::make_unique<Renderer>(*device_->ctx, scene, options_, *previous)
                        : std::make_unique<Renderer>(*device_->ctx, scene, options_);
    }
    raiseWarnings();
    return made;
}

void RendererObject::carryOver() {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(device_->mutex);
    renderer_->setView(view_);
    if (time_) renderer_->setTime(*time_);
    if (lightSet_) renderer_->setLight(light_);
}

void RendererObject::applySceneChanges() {
    const std::shared_ptr<const Scene> changed = sceneObject_->scene;
    if (changed == scene_) return;
    // Settings alone changed: the new renderer takes the old one's parts.
    Renderer* previous = sceneObject_->loads == loads_ ? renderer_.get() : nullptr;
    std::unique_ptr<Renderer> made;
    // A failure after the old renderer gave up its parts leaves it empty: one made anew from the
    // scene it had takes its place, and the error is raised.
    auto restore = [this] {
        if (!renderer_->emptied()) return;
        renderer_ = build(*scene_);
        carryOver();
    };
    try {
        made = build(*changed, previous);
    } catch (const InputError& e) {
        restore();
        throw InputError(std::string(e.what()) +
                         " (the scene's settings as changed since this renderer's last frame; "
                         "set them back to render again, or make a new Renderer at another size)");
    } catch (...) {
        restore();
        throw;
    }
    if (!lightSet_) light_ = changed->light;
    {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(device_->mutex);
        cutsBefore_ += renderer_->cuts();
        renderer_ = std::move(made); // the old one destroyed here, the device held
    }
    carryOver();
    scene_ = changed;
    loads_ = sceneObject_->loads;
    ++rebuilds_;
}

void RendererObject::close() {
    if (!renderer_) return;
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(device_->mutex);
    renderer_.reset();
}

ImageResult RendererObject::render(const IntArg& frames, const std::optional<std::string>& view) {
    open();
    const uint32_t count = countArg("frames", frames.value, 1, 1000000);
    applySceneChanges();
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
    return imageObject(rgbArray(std::move(hdr), size.width, size.height));
}

std::vector<std::string> RendererObject::images() const {
    open();
    return imageNames(false);
}

py::array RendererObject::read(const std::string& name) {
    open();
    if (frames_ == 0) throw InputError(name + ": no frame rendered yet; call render() first");
    const std::vector<std::string> names = images();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        if (renderer_->hasImage(name) && overwritten(name))
            throw InputError("read: '" + name + "' shares its memory with other images of " +
                             "the frame, which overwrite it; name it in keep= when making " +
                             "the renderer (Renderer(scene, keep=['" + name + "'])) to read it");
        throw InputError("read: no image named '" + name +
                         "' in this frame; it has: " + joined(names));
    }
    std::vector<float> rgba;
    VkExtent2D size = renderer_->size();
    locked([&] { rgba = renderer_->readImage(name); });
    // A screen image is read at the output's size; another (the RSM's) at its own.
    const graph::ImageRef ref = renderer_->frameGraph().find(name);
    if (rgba.size() != size_t(size.width) * size.height * 4 && ref.valid())
        size = renderer_->frameGraph().image(ref).extent;
    if (rgba.size() != size_t(size.width) * size.height * 4)
        throw std::runtime_error(name + ": read back an image of an unexpected size");
    // An image of integers as its integers, not as floats of the same bits; but "reprojection",
    // whose words Renderer::readImage decodes (renderer_images.cpp).
    const VkFormat format = ref.valid() && name != "reprojection"
                                ? renderer_->frameGraph().image(ref).format
                                : VK_FORMAT_UNDEFINED;
    if (format == VK_FORMAT_R32_UINT)
        return integerArray<uint32_t>(rgba, size.width, size.height, true);
    if (format == VK_FORMAT_R8_UINT)
        return integerArray<uint8_t>(rgba, size.width, size.height, false);
    return rgbaArray(std::move(rgba), size.width, size.height);
}

void RendererObject::cut() {
    open();
    locked([&] { renderer_->cut(); });
}

py::tuple RendererObject::size() const {
    open();
    return py::make_tuple(renderer_->size().width, renderer_->size().height);
}

uint32_t RendererObject::cuts() const {
    open();
    return cutsBefore_ + renderer_->cuts();
}

std::string RendererObject::device() const {
    return std::string(device_->ctx->properties.deviceName) + " (" + device_->ctx->driverName + ")";
}

std::string RendererObject::repr() const {
    std::string text = "<ssgi.Renderer of " + std::string(py::repr(py::str(sceneObject_->path)));
    if (!renderer_) return text + ", closed>";
    const VkExtent2D size = renderer_->size();
    const uint64_t n = frames_;
    return text + " at " + std::to_string(size.width) + "x" + std::to_string(size.height) +
           ", view " + std::string(py::repr(py::str(view_))) + ", on " +
           std::string(py::repr(py::str(device()))) + ", " + std::to_string(n) +
           (n == 1 ? " frame>" : " frames>");
}

// The names read() finds in the frame: its graph's images, the cached effects' histories, and
// the position the G-buffer's depth gives; with `withOverwritten`, also the transient images a
// later pass overwrites, which keep= can name. Not the graph's unused placeholders
// (temporal.unused*), which hold nothing.
std::vector<std::string> RendererObject::imageNames(bool withOverwritten) const {
    std::vector<std::string> names{"gbuffer.position"};
    for (const auto& image : renderer_->frameGraph().imageMemory())
        if (image.historyPair.empty() && image.name.find(".unused") == std::string::npos)
            names.push_back(image.name);
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
bool RendererObject::overwritten(const std::string& name) const {
    const graph::ImageRef ref = renderer_->frameGraph().find(name);
    return ref.valid() && !renderer_->frameGraph().readable(ref);
}

void RendererObject::open() const {
    if (!renderer_) throw InputError("this renderer is closed");
}

} // namespace ssgi::python
