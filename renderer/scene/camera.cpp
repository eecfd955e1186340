#include "scene/camera.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace ssgi {

glm::mat4 viewMatrix(const Camera& camera) {
    const glm::mat4 rotation = glm::toMat4(glm::conjugate(camera.orientation));
    return rotation * glm::translate(glm::mat4(1.0f), -camera.position);
}

glm::mat4 projectionMatrix(float yfov, float aspect, float znear, float zfar) {
    glm::mat4 p = glm::perspectiveRH_ZO(yfov, aspect, znear, zfar);
    p[1][1] = -p[1][1];
    return p;
}

glm::mat4 projectionMatrix(const Camera& camera, float aspect) {
    return projectionMatrix(camera.yfov, aspect, camera.znear, camera.zfar);
}

glm::quat lookRotation(const glm::vec3& direction, const glm::vec3& up) {
    glm::vec3 d = glm::normalize(direction);
    // Keep the rotation defined when looking straight along `up`.
    glm::vec3 u = std::abs(glm::dot(d, glm::normalize(up))) > 0.999f ? glm::vec3(0, 0, 1) : up;
    return glm::quatLookAtRH(d, u);
}

LightFrustum lightFrustum(const SpotLight& light, const Aabb& bounds) {
    LightFrustum f;
    const glm::vec3 up =
        std::abs(light.direction.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    // Turned at the origin, then moved: position + direction rounds to the position itself once
    // the position's units dwarf 1 (from about 1e8 units: a NaN view and nothing in the RSM).
    f.view = glm::lookAtRH(glm::vec3(0.0f), light.direction, up) *
             glm::translate(glm::mat4(1.0f), -light.position);
    // Far plane: the farthest bounds corner along the axis; near: what depth precision allows.
    float farthest = 0.0f;
    for (int i = 0; i < 8; ++i) {
        glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x,
                         (i & 2) ? bounds.max.y : bounds.min.y,
                         (i & 4) ? bounds.max.z : bounds.min.z);
        farthest = std::max(farthest, glm::dot(corner - light.position, light.direction));
    }
    const float diagonal = glm::length(bounds.size());
    f.zfar = std::max(farthest, 1e-3f * diagonal) * 1.01f;
    f.znear = std::max(f.zfar * 1e-3f, 1e-4f * diagonal);
    const float halfFov = std::min(light.outerConeAngle, glm::radians(85.0f));
    f.tanHalfFov = std::tan(halfFov);
    f.projection = projectionMatrix(2.0f * halfFov, 1.0f, f.znear, f.zfar);
    f.viewProjection = f.projection * f.view;
    return f;
}

bool projectToTexture(const glm::mat4& viewProjection, const glm::vec3& world, glm::vec3& out) {
    const glm::vec4 clip = viewProjection * glm::vec4(world, 1.0f);
    if (clip.w <= 0.0f) return false;
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    out = glm::vec3(ndc.x * 0.5f + 0.5f, ndc.y * 0.5f + 0.5f, ndc.z);
    return true;
}

float linearDepth(float depth, float znear, float zfar) {
    return znear * zfar / (zfar - depth * (zfar - znear));
}

Camera cameraAt(const CameraPath& path, float t) {
    const auto& keys = path.keys;
    if (keys.empty()) return Camera{};
    if (t <= keys.front().time) return keys.front().camera;
    if (t >= keys.back().time) return keys.back().camera;
    size_t i = 1;
    while (keys[i].time < t)
        ++i;
    const CameraKey& a = keys[i - 1];
    const CameraKey& b = keys[i];
    const float s = (t - a.time) / std::max(b.time - a.time, 1e-6f);
    Camera c = a.camera;
    c.position = glm::mix(a.camera.position, b.camera.position, s);
    c.orientation = glm::slerp(a.camera.orientation, b.camera.orientation, s);
    c.yfov = glm::mix(a.camera.yfov, b.camera.yfov, s);
    c.znear = glm::mix(a.camera.znear, b.camera.znear, s);
    c.zfar = glm::mix(a.camera.zfar, b.camera.zfar, s);
    return c;
}

} // namespace ssgi
