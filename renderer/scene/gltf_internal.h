// Internals of the scene loaders, shared between their source files.
#pragma once

#include "scene/gltf_loader.h"
#include "scene/scene.h"

#include <tiny_gltf.h>

#include <set>
#include <string>

namespace ssgi {

// The largest albedo (a base colour's R, G and B) a scene file or a glTF may give: a surface
// reflects at most the light it receives, and the path tracer's estimators assume it.
constexpr float kMaxAlbedo = 1.0f;

// The narrowest field of view (vertical, in degrees) a camera may have: narrower, the projection's
// scale outgrows what 32-bit floats resolve and the image is black.
constexpr float kMinFovDegrees = 0.01f;
// The most a camera's far plane may be beyond its near plane (far / near): the depth buffer and
// the path tracer's rays lose their precision past it.
constexpr float kMaxClipRatio = 1e5f;

// The whole file as bytes; InputError naming it when it is missing or unreadable.
std::string readInputFile(const std::string& path);

// Says each kind of warning once per file: a model with 500 skinned nodes gets one line.
class GltfWarnings {
public:
    explicit GltfWarnings(std::string file) : file_(std::move(file)) {}
    void once(const std::string& message);

private:
    std::string file_;
    std::set<std::string> said_;
};

// Triangle data out of glTF accessors (gltf_mesh.cpp), with every offset, stride, count and
// index checked, so that a malformed file is an InputError, never a read past a buffer's end.
// The Mesh of one TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN primitive (as a triangle list),
// vertices in object space, material left at 0. Without a NORMAL attribute the triangles are
// un-indexed and get their face normals (glTF's flat rule). `where` names the primitive in messages
// ("mesh 3 primitive 0").
Mesh buildPrimitiveMesh(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                        const std::string& file, const std::string& where, GltfWarnings& warnings);

// Walks the file's default scene (gltf_nodes.cpp): one Instance per (node, primitive), meshes
// built once per glTF (mesh, primitive), glTF material m becoming scene material firstMaterial+m.
GltfViewpoint importNodes(const tinygltf::Model& model, const std::string& file, float scale,
                          int firstMaterial, Scene& scene, GltfWarnings& warnings);

} // namespace ssgi
