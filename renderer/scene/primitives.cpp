#include "scene/primitives.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>

namespace ssgi {

glm::vec3 quadNormal(const std::array<glm::vec3, 4>& corners) {
    // The cross product of the diagonals stays meaningful when one of the two triangles is
    // degenerate, unlike the cross product of two edges from one corner.
    // In double precision and made unit length there: at tiny scene units (1e-12) the float
    // product's squared length underflows to 0 and a real quad would seem to have no area.
    const glm::dvec3 normal = glm::cross(glm::dvec3(corners[2] - corners[0]),
                                         glm::dvec3(corners[3] - corners[1]));
    const double length = glm::length(normal);
    return length > 0.0 ? glm::vec3(normal / length) : glm::vec3(0.0f);
}

Mesh makeQuad(const std::array<glm::vec3, 4>& corners, int material) {
    const glm::vec3 normal = glm::normalize(quadNormal(corners));
    const glm::vec2 uvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    Mesh mesh;
    mesh.material = material;
    for (int i = 0; i < 4; ++i)
        mesh.vertices.push_back({corners[i], normal, uvs[i]});
    mesh.indices = {0, 1, 2, 0, 2, 3};
    return mesh;
}

Mesh makeBox(glm::vec3 center, glm::vec3 size, float rotateYDegrees, int material) {
    const glm::mat4 rotation =
        glm::rotate(glm::mat4(1.0f), glm::radians(rotateYDegrees), glm::vec3(0, 1, 0));
    const glm::vec3 half = 0.5f * size;
    Mesh mesh;
    mesh.material = material;
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {1.0f, -1.0f}) {
            // u and v span the face with cross(u, v) = outward normal, so the corners below
            // run counter-clockwise seen from outside.
            glm::vec3 normal(0.0f), u(0.0f), v(0.0f);
            normal[axis] = sign;
            u[(axis + 1) % 3] = 1.0f;
            v[(axis + 2) % 3] = sign;
            const glm::vec3 worldNormal = glm::vec3(rotation * glm::vec4(normal, 0.0f));
            const auto base = static_cast<uint32_t>(mesh.vertices.size());
            const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (glm::vec2 c : corners) {
                const glm::vec3 local = (normal + c.x * u + c.y * v) * half;
                const glm::vec3 world = center + glm::vec3(rotation * glm::vec4(local, 1.0f));
                mesh.vertices.push_back({world, worldNormal, 0.5f * c + 0.5f});
            }
            for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u})
                mesh.indices.push_back(base + i);
        }
    }
    return mesh;
}

Mesh makeSphere(glm::vec3 center, float radius, int segments, int material) {
    const int around = std::max(segments, 3);
    const int rings = std::max(segments / 2, 2);
    Mesh mesh;
    mesh.material = material;
    // The seam column is duplicated so that u runs 0..1 without wrapping.
    for (int ring = 0; ring <= rings; ++ring) {
        const float theta = glm::pi<float>() * float(ring) / float(rings);
        for (int step = 0; step <= around; ++step) {
            const float phi = glm::two_pi<float>() * float(step) / float(around);
            const glm::vec3 normal(std::sin(theta) * std::sin(phi), std::cos(theta),
                                   std::sin(theta) * std::cos(phi));
            const glm::vec2 uv(float(step) / float(around), float(ring) / float(rings));
            mesh.vertices.push_back({center + radius * normal, normal, uv});
        }
    }
    const auto row = static_cast<uint32_t>(around + 1);
    for (uint32_t ring = 0; ring < uint32_t(rings); ++ring) {
        for (uint32_t step = 0; step < uint32_t(around); ++step) {
            const uint32_t a = ring * row + step, b = a + row, c = b + 1, d = a + 1;
            // The pole rows would give zero-area triangles; leave them out.
            if (ring != 0) mesh.indices.insert(mesh.indices.end(), {a, b, d});
            if (ring + 1 != uint32_t(rings)) mesh.indices.insert(mesh.indices.end(), {d, b, c});
        }
    }
    return mesh;
}

} // namespace ssgi
