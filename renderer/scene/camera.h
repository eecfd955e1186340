// Camera and light matrices, and the projection math the screen-space passes rely on. Vulkan
// conventions: right-handed world, depth in [0,1], texture v = 0 at the top of the image.
#pragma once

#include "scene/scene.h"

namespace ssgi {

glm::mat4 viewMatrix(const Camera& camera);
// Perspective projection with y flipped for Vulkan's framebuffer (y down).
glm::mat4 projectionMatrix(float yfov, float aspect, float znear, float zfar);
glm::mat4 projectionMatrix(const Camera& camera, float aspect);

// The spot light's shadow-map frustum: a perspective view from the light along its axis whose
// field of view covers the outer cone, with near/far fitted to the scene bounds.
struct LightFrustum {
    glm::mat4 view{1.0f}, projection{1.0f}, viewProjection{1.0f};
    float znear = 0.01f, zfar = 100.0f;
    float tanHalfFov = 1.0f;
};
LightFrustum lightFrustum(const SpotLight& light, const Aabb& bounds);

// World point -> (u, v, depth): u, v in [0,1] across the image (v down), depth in [0,1].
// Returns false when the point is behind the camera. This is equation (1) of the reverse
// reprojection, C = P V W followed by the divide by w and the NDC -> texture mapping.
bool projectToTexture(const glm::mat4& viewProjection, const glm::vec3& world, glm::vec3& out);

// Linear view distance (along the axis) from a [0,1] depth value of projectionMatrix().
float linearDepth(float depth, float znear, float zfar);

// Interpolated camera at time t (clamped to the path's ends).
Camera cameraAt(const CameraPath& path, float t);

// Rotation that turns the camera's -Z towards `direction` with +Y towards `up`.
glm::quat lookRotation(const glm::vec3& direction, const glm::vec3& up);

} // namespace ssgi
