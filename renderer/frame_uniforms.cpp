// The frame's coordinates as the GPU sees them: its origin, and the mappings from pixels to the
// world that the shaders reconstruct positions with. Pure functions of the scene and the camera.
#include "frame_uniforms.h"

#include <glm/gtx/component_wise.hpp>

namespace ssgi {

// Where the GPU's coordinates have their origin. A float holds about 7 digits, so a scene 1e5
// units from the origin keeps about 1 cm of precision in its G-buffer positions, reprojection
// tests and shadow lookups, and renders visibly wrong. Everything that reaches the GPU is
// therefore moved, in double precision on the CPU, by minus the centre of the scene's bounds:
// geometry (through the instance transforms), camera, light, light frustum and moved boxes; the
// previous frame's matrices were made the same way. A scene near the origin (its centre within
// 16 diagonals) keeps the origin where it is, so that its numbers do not change at all.
glm::dvec3 gpuOrigin(const Aabb& bounds) {
    const glm::dvec3 centre = (glm::dvec3(bounds.min) + glm::dvec3(bounds.max)) * 0.5;
    const double diagonal = glm::length(glm::dvec3(bounds.max) - glm::dvec3(bounds.min));
    // A float itself, so that the GPU's float arithmetic (vertex minus origin, in the instance
    // transform) gives the same exact differences as the CPU's double.
    return glm::compMax(glm::abs(centre)) <= 16.0 * diagonal ? glm::dvec3(0.0)
                                                             : glm::dvec3(glm::vec3(centre));
}

glm::vec3 moved(const glm::vec3& point, const glm::dvec3& origin) {
    return glm::vec3(glm::dvec3(point) - origin);
}

// translate(-origin) * m, in double precision.
glm::mat4 moved(const glm::mat4& m, const glm::dvec3& origin) {
    glm::dmat4 d(m);
    for (int column = 0; column < 4; ++column)
        d[column] -= glm::dvec4(origin * d[column].w, 0.0);
    return glm::mat4(d);
}

// FrameUniforms::pixelToWorld: for the pixel centre p (in pixels of a `size` image) and the view
// depth d there, M (p.x d, p.y d, d, 1) is the world position. The view-space ray through p,
// scaled to reach one unit along the view axis, is affine in p for a perspective projection;
// its three coefficients are found by unprojecting three pixels, in double precision, and
// turned into the world by the view's rotation; the fourth column is the camera's position.
glm::mat4 pixelToWorld(const glm::mat4& view, const glm::mat4& projection, VkExtent2D size) {
    const glm::dmat4 inverseProjection = glm::inverse(glm::dmat4(projection));
    auto rayAt = [&](double x, double y) { // in view space, at view depth 1
        const glm::dvec4 ndc(2.0 * x / size.width - 1.0, 2.0 * y / size.height - 1.0, 0.5, 1.0);
        const glm::dvec4 q = inverseProjection * ndc;
        return glm::dvec3(q) / -q.z;
    };
    const glm::dvec3 origin = rayAt(0.0, 0.0);
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(view));
    const glm::dmat3 rotation(toWorld);
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(rotation * (rayAt(1.0, 0.0) - origin), 0.0);
    m[1] = glm::dvec4(rotation * (rayAt(0.0, 1.0) - origin), 0.0);
    m[2] = glm::dvec4(rotation * origin, 0.0);
    m[3] = toWorld[3];
    return glm::mat4(m);
}

} // namespace ssgi
