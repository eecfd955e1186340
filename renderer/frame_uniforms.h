// The frame's coordinates as the GPU sees them (frame_uniforms.cpp): pure functions of the
// scene's bounds and the camera, made in double precision, which the Renderer puts into the
// frame's uniforms (shared.h FrameUniforms).
#pragma once

#include "scene/scene.h"

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

namespace ssgi {

// The world point the GPU's coordinates have their origin at: the centre of the scene's bounds
// for a scene far from the origin (beyond 16 of its diagonals), else the origin itself. A float
// itself, so that the GPU's float arithmetic gives the same differences as the CPU's double.
glm::dvec3 gpuOrigin(const Aabb& bounds);
// A point, and translate(-origin) * m, moved to the GPU's coordinates in double precision.
glm::vec3 moved(const glm::vec3& point, const glm::dvec3& origin);
glm::mat4 moved(const glm::mat4& m, const glm::dvec3& origin);
// FrameUniforms::pixelToWorld of a view: for the pixel centre p (in pixels of a `size` image)
// and the view depth d there, M (p.x d, p.y d, d, 1) is the world position.
glm::mat4 pixelToWorld(const glm::mat4& view, const glm::mat4& projection, VkExtent2D size);

} // namespace ssgi
