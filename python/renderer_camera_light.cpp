// ssgi.Renderer's camera, light and time (renderer_object.h): set between frames, they apply at
// the next one without a rebuild, the renderer restarting what they invalidate (Renderer::setLight,
// setTime, its cut detection); what is not given stays.
#include "renderer_object.h"

#include "scene/animation.h"
#include "scene/camera.h"
#include "scene/gltf_internal.h" // kMinFovDegrees

#include <pybind11/stl.h>

#include <cmath>

namespace ssgi::python {

namespace {

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

} // namespace

void RendererObject::setTime(const FloatArg& seconds) {
    open();
    const float t = float(numberArg("time", seconds.value, 0.0, 1e9));
    camera_ = cameraAtTime(*scene_, t, sceneObject_->path);
    target_.reset();
    time_ = t;
    locked([&] { renderer_->setTime(t); });
}

void RendererObject::setCamera(const std::optional<Vec3Arg>& position,
                               const std::optional<Vec3Arg>& target,
                               const std::optional<Vec3Arg>& up,
                               const std::optional<FloatArg>& fov) {
    open();
    Camera camera = camera_;
    // What is not given stays: a new position alone keeps looking at the point the camera looked
    // at (its target), not along the same direction.
    const glm::vec3 to = target ? vec3Arg("target", target->value) : lookedAt();
    if (position) camera.position = vec3Arg("position", position->value);
    if (position || target || up) {
        const glm::vec3 upward =
            up ? vec3Arg("up", up->value) : camera_.orientation * glm::vec3(0, 1, 0);
        if (!(glm::length(to - camera.position) > 0.0f))
            throw InputError(target ? "target: the camera's position, so no direction to look in"
                                    : "position: the point the camera looks at (its target), so "
                                      "no direction to look in; give a target too");
        if (!(glm::length(upward) > 0.0f)) throw InputError("up: a zero vector");
        camera.orientation = lookRotation(to - camera.position, upward);
    }
    if (fov) camera.yfov = glm::radians(float(numberArg("fov", fov->value, kMinFovDegrees, 179.0)));
    camera_ = camera;
    if (position || target) target_ = to;
}

// The target given last, else the point of the view ray nearest the scene's centre (where a
// scene file's camera looks), else one unit ahead.
glm::vec3 RendererObject::lookedAt() const {
    if (target_) return *target_;
    const glm::vec3 forward = camera_.orientation * glm::vec3(0, 0, -1);
    const float along = glm::dot(scene_->bounds.center() - camera_.position, forward);
    return camera_.position + forward * (along > 1e-6f ? along : 1.0f);
}

py::dict RendererObject::camera() const {
    py::dict d;
    const glm::vec3 forward = camera_.orientation * glm::vec3(0, 0, -1);
    d["position"] = vec3List(camera_.position);
    // What set_camera takes: the point looked at (its target), the up vector and fov.
    d["target"] = vec3List(lookedAt());
    d["forward"] = vec3List(forward);
    d["up"] = vec3List(camera_.orientation * glm::vec3(0, 1, 0));
    d["fov"] = glm::degrees(camera_.yfov);
    return d;
}

void RendererObject::setLight(
    const std::optional<Vec3Arg>& position, const std::optional<Vec3Arg>& direction,
    const std::optional<Vec3Arg>& target, const std::optional<Vec3Arg>& color,
    const std::optional<FloatArg>& intensity, const std::optional<FloatArg>& cone,
    const std::optional<FloatArg>& innerCone, const std::optional<FloatArg>& radius) {
    open();
    // Checked as a scene file's "light" is (scene_json.cpp's ranges).
    SpotLight l = light_;
    if (target && direction) throw InputError("target: and 'direction' exclude each other");
    if (position) l.position = vec3Arg("position", position->value);
    if (direction) {
        const glm::vec3 d = vec3Arg("direction", direction->value);
        if (!(glm::length(d) > 0.0f)) throw InputError("direction: must not be zero");
        l.direction = glm::normalize(d);
    }
    if (target) {
        const glm::vec3 to = vec3Arg("target", target->value) - l.position;
        if (!(glm::length(to) > 0.0f)) throw InputError("target: equals the light's position");
        l.direction = glm::normalize(to);
    }
    if (color) {
        l.color = vec3Arg("color", color->value);
        for (int i = 0; i < 3; ++i)
            numberArg("color", py::float_(l.color[i]), 0.0, 1e6);
    }
    if (intensity) l.intensity = float(numberArg("intensity", intensity->value, 0.0, 1e12));
    if (radius) l.radius = float(numberArg("radius", radius->value, 0.0, 1e9));
    if (cone) l.outerConeAngle = glm::radians(float(numberArg("cone", cone->value, 1e-3, 89.0)));
    if (innerCone)
        l.innerConeAngle =
            glm::radians(float(numberArg("inner_cone", innerCone->value, 0.0, 89.0)));
    if (!(l.innerConeAngle < l.outerConeAngle))
        throw InputError("inner_cone: " + std::to_string(glm::degrees(l.innerConeAngle)) +
                         " degrees, must be less than the cone's " +
                         std::to_string(glm::degrees(l.outerConeAngle)));
    light_ = l;
    lightSet_ = true;
    locked([&] { renderer_->setLight(light_); });
}

py::dict RendererObject::light() const {
    py::dict d;
    d["position"] = vec3List(light_.position);
    d["direction"] = vec3List(light_.direction);
    d["color"] = vec3List(light_.color);
    d["intensity"] = light_.intensity;
    d["cone"] = glm::degrees(light_.outerConeAngle);
    d["inner_cone"] = glm::degrees(light_.innerConeAngle);
    d["radius"] = light_.radius;
    return d;
}

} // namespace ssgi::python
