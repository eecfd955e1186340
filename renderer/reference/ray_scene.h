// The scene as Embree sees it: every instance baked into world-space triangles, with the
// per-vertex normals, texture coordinates and colours the shading needs, and the alpha mask applied
// as an intersection filter so masked-out texels are holes for every ray (camera, shadow, AO).
#pragma once

#include "scene/scene.h"

#include <memory>
#include <vector>

namespace ssgi::reference {

// What a ray found. Both normals face the side the ray came from (surfaces are two-sided).
struct Surface {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};          // interpolated vertex normal, unit
    glm::vec3 geometricNormal{0.0f, 1.0f, 0.0f}; // the triangle's plane, unit
    glm::vec3 albedo{0.0f};                      // linear, Lambertian
};

class RayScene {
public:
    // Throws std::runtime_error when Embree cannot be started.
    explicit RayScene(const Scene& scene);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // The nearest surface along origin + t * direction (direction unit) for t in [0, tfar).
    bool intersect(glm::vec3 origin, glm::vec3 direction, float tfar, Surface& hit) const;
    // Whether anything lies along origin + t * direction for t in [0, tfar).
    bool occluded(glm::vec3 origin, glm::vec3 direction, float tfar) const;

    // A ray origin just off `surface` on the side `direction` points to, so that the ray does
    // not find the surface it starts from.
    glm::vec3 rayOrigin(const Surface& surface, glm::vec3 direction) const;
    // The length of that offset: small against the scene, large against float rounding.
    float epsilon() const { return epsilon_; }

    // One baked instance: what a hit needs to shade itself (public for the Embree filter).
    struct Geometry {
        std::vector<glm::vec3> positions, normals; // world space
        std::vector<glm::vec2> uvs;
        std::vector<glm::vec4> colors; // Vertex::color as floats; empty without vertex colours
        std::vector<uint32_t> indices; // three per triangle
        const Material* material = nullptr;
        const Texture* texture = nullptr;
    };

private:
    struct Embree;
    std::unique_ptr<Embree> embree_;
    std::vector<std::unique_ptr<Geometry>> geometries_; // indexed by Embree geometry id
    float epsilon_ = 1e-5f;
    float toEmbree_ = 1.0f; // a power of two: world units -> the units Embree sees
};

} // namespace ssgi::reference
