// glTF 2.0 (.gltf/.glb) into the scene model: meshes, materials, base-colour textures, node
// instances, and the file's first camera and light.
#pragma once

#include "scene/scene.h"

#include <optional>
#include <string>
#include <vector>

namespace ssgi {

// What a glTF file says besides geometry, already in world space (after the node transforms and
// the load scale). The scene file decides whether to use them.
struct GltfViewpoint {
    std::optional<Camera> camera;   // first perspective camera node; zfar 0 = "infinite"
    std::optional<SpotLight> light; // first KHR_lights_punctual spot light, else first point light
};

// Appends the default scene (or scene 0) of a glTF file to `scene`: its meshes (object space),
// materials and textures (with index offsets past what `scene` already holds) and one Instance
// per (node, primitive) with the node's world matrix times a uniform `scale`. Throws InputError
// naming the file and the problem; warns on stderr (once per kind) about what it ignores.
GltfViewpoint loadGltf(const std::string& path, float scale, Scene& scene);

// Every file the scene loaders have read in this process, in order: scene files, glTFs, their
// buffers and images (as opened). What a program must not write over (checkRunFiles).
std::vector<std::string> filesRead();

} // namespace ssgi
