// What a bare glTF (no scene file) is given so that it comes out framed and lit: a camera, a
// spot light, a daylight sky and, where it has no floor of its own, a ground plane. Each is a
// pure function of the model's bounds (and the camera), so that one rule serves models in
// millimetres and in kilometres alike. docs/bare-models.md states the rules for users.
#pragma once

#include "scene/scene.h"

namespace ssgi {

// A raised three-quarter view (from the front-right, +Z being glTF's front, 30 degrees above
// the horizon) of the bounds' centre, as close as lets all eight corners of the bounds fit
// within 90% of a square image's 45 degree field of view. Clip planes are left at 0 for the
// loader to fit.
Camera bareModelCamera(const Aabb& model);

// A spot light above the camera and to its right (55 degrees up, turned 40 degrees from the
// camera about the vertical), aimed at the centre from four bounding-sphere radii, so it lies
// outside the bounds. Its full-intensity cone covers the bounding sphere, and its intensity
// gives an irradiance of kBareModelIrradiance at the centre: intensity grows with the
// distance squared, so the exposure does not depend on the model's units.
SpotLight bareModelLight(const Aabb& model, const Camera& camera);
constexpr float kBareModelIrradiance = 1.5f;

// A soft daylight sky: pale blue zenith, near-white horizon; below the horizon the colour a
// far-off ground plane shows in the sky's light, so the plane's edge does not show.
Sky daylightSky();

// True when the model has a floor of its own: the upward-facing triangles lying within the
// lowest 1% of its height cover, seen from above, at least half of its footprint (the bounds'
// x-z area). The flat base of a closed object faces down, so it does not count.
bool hasGround(const Scene& scene, const Aabb& model);

// Adds a grey quad facing up at the model's lowest point (a closed model stands on it), reaching 25
// bounding- sphere radii from its centre (far enough to fill the view of bareModelCamera), as its
// own material and an instance named "ground". Does not touch the scene's bounds.
void addGroundPlane(Scene& scene, const Aabb& model);
constexpr float kGroundAlbedo = 0.5f;

} // namespace ssgi
