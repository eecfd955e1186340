#include "reference/lighting.h"

#include <algorithm>
#include <cmath>

namespace ssgi::reference {

float spotAttenuation(const SpotLight& light, glm::vec3 fromLight) {
    const float cosOuter = std::cos(light.outerConeAngle);
    const float cosInner = std::cos(light.innerConeAngle);
    // The same guard as the shader, so that equal cones give the same hard edge.
    const float t = std::clamp((glm::dot(fromLight, light.direction) - cosOuter) /
                                   std::max(cosInner - cosOuter, 1e-4f),
                               0.0f, 1.0f);
    return t * t;
}

glm::vec3 skyRadiance(const Sky& sky, glm::vec3 direction) {
    return direction.y >= 0.0f ? glm::mix(sky.horizon, sky.zenith, direction.y) : sky.ground;
}

glm::vec3 spotIrradiance(const RayScene& rays, const SpotLight& light, const Surface& surface,
                         Rng& rng) {
    glm::vec3 emitter = light.position;
    if (light.radius > 0.0f) {
        glm::vec3 t, b;
        orthonormalBasis(light.direction, t, b);
        const glm::vec2 d = uniformDisk(rng.uniform2());
        emitter += light.radius * (d.x * t + d.y * b);
    }
    const glm::vec3 toLight = emitter - surface.position;
    const float distance2 = glm::dot(toLight, toLight);
    if (!(distance2 > 0.0f)) return glm::vec3(0.0f);
    const float distance = std::sqrt(distance2);
    const glm::vec3 l = toLight / distance;
    const float cosSurface = glm::dot(surface.normal, l);
    // Light arriving from behind the triangle's plane would have to pass through it.
    if (cosSurface <= 0.0f || glm::dot(surface.geometricNormal, l) <= 0.0f) return glm::vec3(0.0f);
    // The cone is narrower than 90 degrees, so this also makes the disk one-sided.
    const float spot = spotAttenuation(light, -l);
    if (spot <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 origin = rays.rayOrigin(surface, l);
    const float reach = glm::length(emitter - origin) - rays.epsilon();
    if (reach > 0.0f && rays.occluded(origin, l, reach)) return glm::vec3(0.0f);
    return light.color * light.intensity * spot * cosSurface / distance2;
}

} // namespace ssgi::reference
