// Moving objects: the scene posed at a time along its object paths.
#pragma once

#include "scene/scene.h"

#include <vector>

namespace ssgi {

// Links every object path to the instances named by its `object`, and widens the scene's bounds
// to every place the paths take them; InputError naming `file` for a path that names no object.
void resolveObjectPaths(Scene& scene, const std::string& file);

// The translation a path gives at `time`: linear between keys, the end keys' beyond them.
glm::vec3 translationAt(const ObjectPath& path, float time);

// Every instance's world transform at `time` (instances on no path keep theirs).
std::vector<glm::mat4> instanceTransformsAt(const Scene& scene, float time);

// A copy of the scene with its instances placed as they are at `time` (for the reference).
Scene posedAt(const Scene& scene, float time);

// The camera at `time` (>= 0) along the scene's camera path, else the scene's own camera; an
// InputError naming `sceneName` when the scene has neither a camera path nor object paths, so
// that a time means nothing to it.
Camera cameraAtTime(const Scene& scene, float time, const std::string& sceneName);

// An instance's world-space bounding box under `transform`.
Aabb instanceBounds(const Scene& scene, size_t instance, const glm::mat4& transform);

} // namespace ssgi
