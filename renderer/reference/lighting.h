// The light sources, defined exactly as the real-time renderer defines them (common.glsl):
// the spot light's glTF cone falloff, the sky's vertical gradient, and the spot light as a
// one-sided emitting disk of the scene's radius for soft shadows.
#pragma once

#include "reference/random.h"
#include "reference/ray_scene.h"

namespace ssgi::reference {

// glTF KHR_lights_punctual: t = clamp((cos - cos outer) / (cos inner - cos outer)), s = t^2,
// with `fromLight` the unit direction from the light toward the point.
float spotAttenuation(const SpotLight& light, glm::vec3 fromLight);

// Radiance of the sky toward `direction` (unit): the gradient above the horizon, `ground`
// below it.
glm::vec3 skyRadiance(const Sky& sky, glm::vec3 direction);

// One-sample estimate of the irradiance the spot light delivers to `surface` (through its
// shading normal), shadows included. Radius 0: the point light, exactly. Radius r > 0: a point
// y drawn uniformly on the disk, whose radiance toward w is I(w) / (pi r^2 cos theta_e), so
// the estimate is I(w_y) cos(theta_p) / d_y^2 * V(y), and r -> 0 gives the point light.
glm::vec3 spotIrradiance(const RayScene& rays, const SpotLight& light, const Surface& surface,
                         Rng& rng);

} // namespace ssgi::reference
