// Internals of the scene loaders, shared between their source files.
#pragma once

#include "scene/gltf_loader.h"
#include "scene/scene.h"

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <memory>
#include <set>
#include <string>
#include <vector>

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

// The glTF at `path` (.gltf or .glb) parsed, its buffers and images read from beside it
// (gltf_files.cpp); InputError naming the file and the problem.
tinygltf::Model readGltfModel(const std::string& path);

// Says each kind of warning once per file: a model with 500 skinned nodes gets one line.
class GltfWarnings {
public:
    explicit GltfWarnings(std::string file) : file_(std::move(file)) {}
    void once(const std::string& message);

private:
    std::string file_;
    std::set<std::string> said_;
};

// The checks of a glTF's JSON around tinygltf's reading (gltf_json_checks.cpp). gltfJson: the
// JSON of a .gltf, or of a .glb's JSON chunk; null when it is not JSON (tinygltf says why).
// checkGltfJsonFirst, before tinygltf reads the file: what it refuses with a wrong message or
// reads against the specification (extension lists that are not arrays of names, a byteStride
// glTF does not allow). checkGltfJson, after: what tinygltf takes without a word (a value of the
// wrong kind, a fraction or a number beyond 32 bits, an index below zero), and each extension
// the loader does not read, named once. InputError naming the file and the problem.
nlohmann::json gltfJson(const std::string& bytes, bool binary);
void checkGltfJsonFirst(const std::string& path, const nlohmann::json& root);
void checkGltfJson(const std::string& path, const nlohmann::json& root, GltfWarnings& warnings);

// One accessor's elements after its offsets and length have been checked against its buffer
// (gltf_accessor.cpp), so reading any element below `count` stays inside the buffer.
struct AccessorView {
    const uint8_t* data = nullptr; // null: no bufferView, so every element is zero (glTF rule)
    size_t stride = 0;
    size_t count = 0;
    int componentType = 0;
    int componentSize = 0;
    bool normalized = false;
    std::shared_ptr<std::vector<uint8_t>> dense; // a sparse accessor's elements, made dense

    // Component c of an element as a float (normalized integers mapped as glTF says).
    float component(size_t element, int c) const;
    // An element of an unsigned integer SCALAR accessor.
    uint32_t index(size_t element) const;
};

// Accessor `index` checked to be a `type` (TINYGLTF_TYPE_*) of one of `allowedComponents`, the
// component types the glTF spec allows for this use; a normalized integer type is written as its
// negative (-UNSIGNED_BYTE = normalized unsigned byte). A sparse accessor is made dense, its
// indices and values checked as any other data. `what` names the use in messages.
AccessorView viewAccessor(const tinygltf::Model& model, int index, int type,
                          std::initializer_list<int> allowedComponents, const std::string& file,
                          const std::string& what);

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
