#include "scene/gltf_internal.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <numeric>

namespace ssgi {

void GltfWarnings::once(const std::string& message) {
    if (said_.insert(message).second) std::cerr << "warning: " << file_ << ": " << message << "\n";
}

namespace {

template <typename T> T load(const uint8_t* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T)); // glTF data need not be aligned for T
    return value;
}

// One accessor's elements after its offsets and length have been checked against its buffer,
// so reading any element below `count` stays inside the buffer.
struct AccessorView {
    const uint8_t* data = nullptr; // null: no bufferView, so every element is zero (glTF rule)
    size_t stride = 0;
    size_t count = 0;
    int componentType = 0;
    int componentSize = 0;
    bool normalized = false;

    float component(size_t element, int c) const {
        if (!data) return 0.0f;
        const uint8_t* p = data + element * stride + size_t(c) * size_t(componentSize);
        switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return load<float>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? *p / 255.0f : *p;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const float v = load<uint16_t>(p);
            return normalized ? v / 65535.0f : v;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float v = load<int8_t>(p);
            return normalized ? std::max(v / 127.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const float v = load<int16_t>(p);
            return normalized ? std::max(v / 32767.0f, -1.0f) : v;
        }
        default:
            return float(load<uint32_t>(p));
        }
    }
    uint32_t index(size_t element) const {
        if (!data) return 0;
        const uint8_t* p = data + element * stride;
        switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return *p;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return load<uint16_t>(p);
        default:
            return load<uint32_t>(p);
        }
    }
};

[[noreturn]] void fail(const std::string& file, const std::string& problem) {
    throw InputError(file + ": " + problem);
}

std::string typeName(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
        return "VEC2";
    case TINYGLTF_TYPE_VEC3:
        return "VEC3";
    case TINYGLTF_TYPE_VEC4:
        return "VEC4";
    default:
        return "type " + std::to_string(type);
    }
}

// `allowedComponents` lists the component types the glTF spec allows for this use; a normalized
// integer type is written as its negative (-UNSIGNED_BYTE = normalized unsigned byte).
AccessorView viewAccessor(const tinygltf::Model& model, int index, int type,
                          std::initializer_list<int> allowedComponents, const std::string& file,
                          const std::string& what) {
    if (index < 0 || size_t(index) >= model.accessors.size())
        fail(file, what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& accessor = model.accessors[size_t(index)];
    const int code = accessor.normalized ? -accessor.componentType : accessor.componentType;
    if (std::find(allowedComponents.begin(), allowedComponents.end(), code) ==
        allowedComponents.end())
        fail(file, what + ": component type " + std::to_string(accessor.componentType) +
                       (accessor.normalized ? " (normalized)" : "") + " is not allowed here");
    if (accessor.type != type)
        fail(file,
             what + ": accessor is " + typeName(accessor.type) + ", expected " + typeName(type));
    if (accessor.sparse.isSparse) fail(file, what + ": sparse accessors are not supported");

    AccessorView view;
    view.count = accessor.count;
    view.componentType = accessor.componentType;
    view.componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
    view.normalized = accessor.normalized;
    if (accessor.bufferView < 0) return view;
    if (size_t(accessor.bufferView) >= model.bufferViews.size())
        fail(file,
             what + ": buffer view " + std::to_string(accessor.bufferView) + " does not exist");
    const tinygltf::BufferView& bufferView = model.bufferViews[size_t(accessor.bufferView)];
    if (bufferView.buffer < 0 || size_t(bufferView.buffer) >= model.buffers.size())
        fail(file, what + ": buffer " + std::to_string(bufferView.buffer) + " does not exist");
    const std::vector<unsigned char>& buffer = model.buffers[size_t(bufferView.buffer)].data;
    if (bufferView.byteOffset > buffer.size() ||
        bufferView.byteLength > buffer.size() - bufferView.byteOffset)
        fail(file, what + ": buffer view " + std::to_string(accessor.bufferView) +
                       " runs past the end of its buffer (truncated file?)");
    const size_t elementSize =
        size_t(view.componentSize) * size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
    view.stride = bufferView.byteStride ? bufferView.byteStride : elementSize;
    if (view.stride < elementSize)
        fail(file,
             what + ": byteStride " + std::to_string(view.stride) + " is smaller than one element");
    if (view.count > 0) {
        const bool fits =
            accessor.byteOffset <= bufferView.byteLength &&
            elementSize <= bufferView.byteLength - accessor.byteOffset &&
            view.count - 1 <=
                (bufferView.byteLength - accessor.byteOffset - elementSize) / view.stride;
        if (!fits)
            fail(file, what + ": " + std::to_string(view.count) +
                           " elements run past the end of buffer view " +
                           std::to_string(accessor.bufferView));
    }
    // The specification requires both; read anyway, the bytes would be other numbers (a shifted
    // float is a tiny or huge one) and the error would be found far from its cause.
    const size_t offset = bufferView.byteOffset + accessor.byteOffset;
    if (offset % size_t(view.componentSize) != 0 || view.stride % size_t(view.componentSize) != 0)
        fail(file, what + ": accessor " + std::to_string(index) + " starts at byte " +
                       std::to_string(offset) + " of its buffer with a stride of " +
                       std::to_string(view.stride) + ", not both multiples of its " +
                       std::to_string(view.componentSize) +
                       "-byte components (unaligned; the glTF specification requires them)");
    view.data = buffer.data() + offset;
    return view;
}

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 unitOr(glm::vec3 v, glm::vec3 fallback) {
    const float length = glm::length(v);
    return length > 0.0f && std::isfinite(length) ? v / length : fallback;
}

// Scanned and converted models sometimes carry zero or NaN normals (at degenerate triangles);
// those vertices get the area-weighted normal of the triangles around them instead.
void repairNormals(Mesh& mesh, GltfWarnings& warnings) {
    std::vector<bool> broken(mesh.vertices.size(), false);
    bool anyBroken = false;
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        glm::vec3& n = mesh.vertices[i].normal;
        const float length = glm::length(n);
        if (length > 1e-20f && std::isfinite(length)) {
            n /= length;
        } else {
            broken[i] = anyBroken = true;
            n = glm::vec3(0.0f);
        }
    }
    if (!anyBroken) return;
    warnings.once("NORMAL vectors of zero length or not finite were replaced by face normals");
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        Vertex* corner[3] = {&mesh.vertices[mesh.indices[t]], &mesh.vertices[mesh.indices[t + 1]],
                             &mesh.vertices[mesh.indices[t + 2]]};
        const glm::vec3 areaNormal = glm::cross(corner[1]->position - corner[0]->position,
                                                corner[2]->position - corner[0]->position);
        for (int c = 0; c < 3; ++c)
            if (broken[mesh.indices[t + size_t(c)]]) corner[c]->normal += areaNormal;
    }
    for (size_t i = 0; i < mesh.vertices.size(); ++i)
        if (broken[i]) mesh.vertices[i].normal = unitOr(mesh.vertices[i].normal, {0, 1, 0});
}

// The corners of a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN primitive as a triangle list, in
// the order the glTF specification (§3.7.2.1) gives each triangle, so that the front faces stay
// the front faces: strip triangle i is (i, i+1+i%2, i+2-i%2), fan triangle i is (i+1, i+2, 0).
std::vector<uint32_t> triangleList(std::vector<uint32_t> corners, int mode) {
    if (mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) return corners;
    std::vector<uint32_t> list;
    const size_t triangles = corners.size() < 3 ? 0 : corners.size() - 2;
    list.reserve(triangles * 3);
    for (size_t i = 0; i < triangles; ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
            list.insert(list.end(), {corners[i], corners[i + 1 + i % 2], corners[i + 2 - i % 2]});
        else
            list.insert(list.end(), {corners[i + 1], corners[i + 2], corners[0]});
    }
    return list;
}

} // namespace

Mesh buildPrimitiveMesh(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                        const std::string& file, const std::string& where, GltfWarnings& warnings) {
    auto attribute = [&](const char* name) {
        auto it = primitive.attributes.find(name);
        return it == primitive.attributes.end() ? -1 : it->second;
    };
    constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
    if (attribute("POSITION") < 0) fail(file, where + " has no POSITION attribute");
    const AccessorView positions = viewAccessor(model, attribute("POSITION"), TINYGLTF_TYPE_VEC3,
                                                {kFloat}, file, where + " POSITION");
    const size_t vertexCount = positions.count;
    std::vector<glm::vec3> points(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) {
        points[i] = {positions.component(i, 0), positions.component(i, 1),
                     positions.component(i, 2)};
        if (!finite(points[i]))
            fail(file, where + ": POSITION " + std::to_string(i) + " is not a finite number");
    }

    std::vector<uint32_t> corners(vertexCount);
    if (primitive.indices >= 0) {
        const AccessorView indices = viewAccessor(model, primitive.indices, TINYGLTF_TYPE_SCALAR,
                                                  {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                                                  file, where + " indices");
        corners.resize(indices.count);
        for (size_t i = 0; i < indices.count; ++i) {
            corners[i] = indices.index(i);
            if (corners[i] >= vertexCount)
                fail(file, where + ": index " + std::to_string(corners[i]) + " (entry " +
                               std::to_string(i) + ") is out of range for " +
                               std::to_string(vertexCount) + " vertices");
        }
    } else {
        std::iota(corners.begin(), corners.end(), 0u);
    }
    corners = triangleList(std::move(corners), primitive.mode);
    if (corners.size() % 3 != 0)
        fail(file, where + ": " + std::to_string(corners.size()) +
                       " triangle corners is not a multiple of 3");

    std::vector<glm::vec2> uvs(vertexCount, glm::vec2(0.0f));
    if (attribute("TEXCOORD_0") >= 0) {
        const AccessorView view = viewAccessor(model, attribute("TEXCOORD_0"), TINYGLTF_TYPE_VEC2,
                                               {kFloat, -TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                -TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                               file, where + " TEXCOORD_0");
        if (view.count != vertexCount) fail(file, where + ": TEXCOORD_0 count != POSITION count");
        for (size_t i = 0; i < vertexCount; ++i) {
            uvs[i] = {view.component(i, 0), view.component(i, 1)};
            if (!std::isfinite(uvs[i].x) || !std::isfinite(uvs[i].y))
                fail(file, where + ": TEXCOORD_0 " + std::to_string(i) + " is not finite");
        }
    }

    Mesh mesh;
    if (attribute("NORMAL") >= 0) {
        const AccessorView normals = viewAccessor(model, attribute("NORMAL"), TINYGLTF_TYPE_VEC3,
                                                  {kFloat}, file, where + " NORMAL");
        if (normals.count != vertexCount) fail(file, where + ": NORMAL count != POSITION count");
        mesh.vertices.resize(vertexCount);
        for (size_t i = 0; i < vertexCount; ++i) {
            const glm::vec3 n(normals.component(i, 0), normals.component(i, 1),
                              normals.component(i, 2));
            mesh.vertices[i] = {points[i], n, uvs[i]};
        }
        mesh.indices = std::move(corners);
        repairNormals(mesh, warnings);
        return mesh;
    }
    // Flat shading needs a normal per triangle, so no vertex may be shared between triangles.
    mesh.vertices.reserve(corners.size());
    mesh.indices.resize(corners.size());
    std::iota(mesh.indices.begin(), mesh.indices.end(), 0u);
    for (size_t t = 0; t < corners.size(); t += 3) {
        const glm::vec3 a = points[corners[t]], b = points[corners[t + 1]],
                        c = points[corners[t + 2]];
        // Degenerate triangles cover no pixel; any unit normal will do for them.
        const glm::vec3 normal = unitOr(glm::cross(b - a, c - a), {0, 1, 0});
        for (size_t k = 0; k < 3; ++k)
            mesh.vertices.push_back({points[corners[t + k]], normal, uvs[corners[t + k]]});
    }
    return mesh;
}

} // namespace ssgi
