#include "scene/gltf_internal.h"
#include "scene/warnings.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <numeric>

namespace ssgi {

void GltfWarnings::once(const std::string& message) {
    if (said_.insert(message).second) warn(file_ + ": " + message);
}

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& problem) {
    throw InputError(file + ": " + problem);
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

// COLOR_0 (VEC3 or VEC4 of floats or normalized unsigned bytes or shorts; glTF 2.0 section
// 3.7.2.1) as the scene model's 16-bit RGBA, alpha 1 where the file gives RGB.
std::vector<glm::u16vec4> vertexColors(const tinygltf::Model& model, int accessor,
                                       size_t vertexCount, const std::string& file,
                                       const std::string& where) {
    const bool rgba = accessor >= 0 && size_t(accessor) < model.accessors.size() &&
                      model.accessors[size_t(accessor)].type == TINYGLTF_TYPE_VEC4;
    const AccessorView view =
        viewAccessor(model, accessor, rgba ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                     {TINYGLTF_COMPONENT_TYPE_FLOAT, -TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                      -TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                     file, where + " COLOR_0");
    if (view.count != vertexCount) fail(file, where + ": COLOR_0 count != POSITION count");
    std::vector<glm::u16vec4> colors(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i)
        for (int c = 0; c < 4; ++c) {
            const float value = c < 3 || rgba ? view.component(i, c) : 1.0f;
            // Float colours outside [0, 1] are invalid glTF; NaN would pass a clamp unnoticed.
            if (!(value >= 0.0f && value <= 1.0f))
                fail(file, where + ": COLOR_0 " + std::to_string(i) + " is not within [0, 1]");
            colors[i][c] = uint16_t(std::lround(value * 65535.0f));
        }
    return colors;
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
    std::vector<glm::u16vec4> colors(vertexCount, glm::u16vec4(65535));
    if (attribute("COLOR_0") >= 0) {
        colors = vertexColors(model, attribute("COLOR_0"), vertexCount, file, where);
        mesh.vertexColors = true;
    }
    if (attribute("NORMAL") >= 0) {
        const AccessorView normals = viewAccessor(model, attribute("NORMAL"), TINYGLTF_TYPE_VEC3,
                                                  {kFloat}, file, where + " NORMAL");
        if (normals.count != vertexCount) fail(file, where + ": NORMAL count != POSITION count");
        mesh.vertices.resize(vertexCount);
        for (size_t i = 0; i < vertexCount; ++i) {
            const glm::vec3 n(normals.component(i, 0), normals.component(i, 1),
                              normals.component(i, 2));
            mesh.vertices[i] = {points[i], n, uvs[i], colors[i]};
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
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t corner = corners[t + k];
            mesh.vertices.push_back({points[corner], normal, uvs[corner], colors[corner]});
        }
    }
    return mesh;
}

} // namespace ssgi
