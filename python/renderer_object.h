// ssgi.Renderer's object: the real-time renderer of a Scene on a device, driven as the render
// program drives it. Its scene, camera, light and view may change between frames: each applies
// at the next frame (renderer.cpp says how; the camera, the light and the time are in
// renderer_camera_light.cpp); the bindings are in renderer_api.cpp.
#pragma once

#include "device.h"
#include "module.h"

#include "renderer.h"

#include <atomic>
#include <optional>

namespace ssgi::python {

class RendererObject {
public:
    RendererObject(const std::shared_ptr<SceneObject>& scene, const SizeArg& size,
                   const std::optional<std::string>& device, const std::string& view,
                   const NamesArg& keep);
    ~RendererObject() { close(); }

    void close();
    ImageResult render(const IntArg& frames, const std::optional<std::string>& view);
    std::vector<std::string> images() const; // the names read() accepts
    py::array read(const std::string& name);
    void setTime(const FloatArg& seconds);
    void setCamera(const std::optional<Vec3Arg>& position, const std::optional<Vec3Arg>& target,
                   const std::optional<Vec3Arg>& up, const std::optional<FloatArg>& fov);
    py::dict camera() const;
    void setLight(const std::optional<Vec3Arg>& position, const std::optional<Vec3Arg>& direction,
                  const std::optional<Vec3Arg>& target, const std::optional<Vec3Arg>& color,
                  const std::optional<FloatArg>& intensity, const std::optional<FloatArg>& cone,
                  const std::optional<FloatArg>& innerCone, const std::optional<FloatArg>& radius);
    py::dict light() const;
    void cut();
    py::dict profile() const;
    py::dict memory() const;
    py::tuple size() const;
    const std::string& view() const { return view_; }
    uint32_t cuts() const;
    uint64_t frames() const { return frames_; }
    uint32_t rebuilds() const { return rebuilds_; }
    bool closed() const { return !renderer_; }
    std::string device() const;
    bool validation() const { return device_->ctx->validationEnabled; }
    const std::shared_ptr<SceneObject>& scene() const { return sceneObject_; }
    std::string repr() const;

private:
    // The scene changed since the renderer was built (its settings: a new Scene behind the
    // SceneObject): builds the renderer again from it, keeping the camera, the light, the time
    // and the view, as the viewer's panel does; from the old renderer's parts where only the
    // settings changed (its scene on the device, its pipelines). With the GIL held.
    void applySceneChanges();
    // A renderer of `scene`, made from `previous`'s parts where given (Renderer's taking
    // constructor: the same geometry, other settings).
    std::unique_ptr<Renderer> build(const Scene& scene, Renderer* previous = nullptr);
    // Carries the camera's time, the light and the view over to renderer_ (made anew).
    void carryOver();
    std::vector<std::string> imageNames(bool withOverwritten) const;
    bool overwritten(const std::string& name) const;
    void open() const;
    // Runs `f` on the renderer with the GIL released and the device held (another thread may be
    // rendering on it).
    template <class F> void locked(F&& f) const {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(device_->mutex);
        f();
    }

    std::shared_ptr<Device> device_;
    std::shared_ptr<SceneObject> sceneObject_; // the Python scene, whose changes apply
    std::shared_ptr<const Scene> scene_;       // the scene the renderer was built from
    uint64_t loads_ = 0;                       // its SceneObject::loads then
    std::unique_ptr<Renderer> renderer_;
    RenderOptions options_;
    Camera camera_;
    // The point the camera looks at, as set_camera's target gave it; none: lookedAt() finds it.
    std::optional<glm::vec3> target_;
    glm::vec3 lookedAt() const;
    SpotLight light_;           // the light as set (the scene's until set_light)
    bool lightSet_ = false;     // set_light was called
    std::optional<float> time_; // the last set_time
    std::string view_;
    uint32_t cutsBefore_ = 0; // of the renderers built before this one
    uint32_t rebuilds_ = 0;   // times the scene's changes rebuilt the renderer
    // Frames rendered so far; read by another thread while render() runs.
    std::atomic<uint64_t> frames_{0};
    uint64_t framesOfThis_ = 0; // of the renderer as built last
};

} // namespace ssgi::python
