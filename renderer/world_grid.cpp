#include "world_grid.h"

#include <algorithm>
#include <cmath>

namespace ssgi {

namespace {

// A polygon's corner: where it lies in clip space and in the space the transforms give.
struct Corner {
    glm::vec4 clip;
    glm::vec3 world;
};

// The clip-space planes' signed distances (inside where >= 0): x, y in [-w, w], z in [0, w].
float planeDistance(const glm::vec4& c, int plane) {
    switch (plane) {
    case 0:
        return c.w + c.x;
    case 1:
        return c.w - c.x;
    case 2:
        return c.w + c.y;
    case 3:
        return c.w - c.y;
    case 4:
        return c.z;
    default:
        return c.w - c.z;
    }
}

} // namespace

Aabb boundsInFrustum(const Scene& scene, const std::vector<glm::mat4>& transforms,
                     const glm::mat4& viewProjection) {
    Aabb box;
    std::vector<Corner> polygon, clipped;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const Mesh& mesh = scene.meshes[size_t(instance.mesh)];
        const glm::mat4& toWorld = transforms[i];
        const size_t count = mesh.indices.empty() ? mesh.vertices.size() : mesh.indices.size();
        for (size_t t = 0; t + 2 < count; t += 3) {
            polygon.clear();
            for (size_t k = 0; k < 3; ++k) {
                const uint32_t index = mesh.indices.empty() ? uint32_t(t + k) : mesh.indices[t + k];
                const glm::vec3 world =
                    glm::vec3(toWorld * glm::vec4(mesh.vertices[index].position, 1.0f));
                polygon.push_back({viewProjection * glm::vec4(world, 1.0f), world});
            }
            // Sutherland-Hodgman, one plane at a time.
            for (int plane = 0; plane < 6 && !polygon.empty(); ++plane) {
                clipped.clear();
                for (size_t k = 0; k < polygon.size(); ++k) {
                    const Corner& a = polygon[k];
                    const Corner& b = polygon[(k + 1) % polygon.size()];
                    const float da = planeDistance(a.clip, plane);
                    const float db = planeDistance(b.clip, plane);
                    if (da >= 0.0f) clipped.push_back(a);
                    if ((da >= 0.0f) != (db >= 0.0f)) {
                        const float s = da / (da - db);
                        clipped.push_back(
                            {a.clip + (b.clip - a.clip) * s, a.world + (b.world - a.world) * s});
                    }
                }
                std::swap(polygon, clipped);
            }
            for (const Corner& c : polygon)
                box.extend(c.world);
        }
    }
    return box;
}

WorldGridPlacement placeWorldGrid(const Aabb& box, int voxels) {
    WorldGridPlacement grid;
    if (box.empty()) return grid;
    const glm::vec3 extent = box.size();
    const float longest = std::max({extent.x, extent.y, extent.z});
    // The box's own scale: a flat box (one floor) still gets voxels of a sensible side.
    const float side = std::max(longest, 1e-6f * glm::length(box.max) + 1e-30f);
    grid.voxel = side / float(voxels - 2);
    grid.origin = box.min - glm::vec3(grid.voxel);
    for (int axis = 0; axis < 3; ++axis)
        grid.size[axis] = std::clamp(int(std::ceil(extent[axis] / grid.voxel)) + 2, 1, voxels);
    return grid;
}

} // namespace ssgi
