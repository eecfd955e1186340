// The node hierarchy of a glTF file: instances, the first camera and the first light.
#include "scene/gltf_internal.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace ssgi {
namespace {

[[noreturn]] void fail(const std::string& file, const std::string& problem) {
    throw InputError(file + ": " + problem);
}

// Real scenes nest a few dozen levels; the walk recurses once per level, so a deeper chain (a
// malformed or hostile file) would overflow the stack before anything else noticed.
constexpr int kMaxNodeDepth = 1000;

bool finite(const glm::mat4& m) {
    for (int i = 0; i < 16; ++i)
        if (!std::isfinite(glm::value_ptr(m)[i])) return false;
    return true;
}
bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::mat4 localTransform(const tinygltf::Node& node, const std::string& file, int index) {
    const std::string what = "node " + std::to_string(index);
    glm::mat4 local(1.0f);
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) fail(file, what + ": matrix needs 16 numbers");
        // Column-major in glTF and in glm alike.
        for (int i = 0; i < 16; ++i)
            glm::value_ptr(local)[i] = float(node.matrix[size_t(i)]);
    } else {
        const auto& t = node.translation;
        const auto& r = node.rotation;
        const auto& s = node.scale;
        if ((!t.empty() && t.size() != 3) || (!r.empty() && r.size() != 4) ||
            (!s.empty() && s.size() != 3))
            fail(file, what + ": translation, rotation or scale has the wrong length");
        if (!t.empty()) local = glm::translate(local, glm::vec3(t[0], t[1], t[2]));
        // glTF stores quaternions as x, y, z, w; glm's constructor takes w first.
        if (!r.empty()) local *= glm::mat4_cast(glm::normalize(glm::quat(r[3], r[0], r[1], r[2])));
        if (!s.empty()) local = glm::scale(local, glm::vec3(s[0], s[1], s[2]));
    }
    if (!finite(local)) fail(file, what + ": transform is not finite");
    return local;
}

// A quaternion turning -Z and +Y into the node's own -Z and +Y, whatever its scale.
glm::quat orientationOf(const glm::mat4& world) {
    const glm::vec3 forward = glm::normalize(glm::mat3(world) * glm::vec3(0, 0, -1));
    return glm::quatLookAtRH(forward, glm::mat3(world) * glm::vec3(0, 1, 0));
}

class NodeImporter {
public:
    NodeImporter(const tinygltf::Model& model, const std::string& file, float scale,
                 int firstMaterial, Scene& scene, GltfWarnings& warnings)
        : model_(model), file_(file), scale_(scale), firstMaterial_(firstMaterial), scene_(scene),
          warnings_(warnings), onPath_(model.nodes.size(), false),
          visited_(model.nodes.size(), false) {}

    void importNode(int index, const glm::mat4& parent, int depth = 0) {
        if (index < 0 || size_t(index) >= model_.nodes.size())
            fail(file_, "node " + std::to_string(index) + " does not exist");
        // A node under itself would recurse forever; the glTF spec forbids it.
        if (onPath_[size_t(index)])
            fail(file_, "node " + std::to_string(index) + " is its own ancestor");
        // glTF node trees are disjoint. A node reached twice would be drawn twice, and a chain
        // of nodes each listing the next twice would multiply the instances exponentially.
        if (visited_[size_t(index)])
            fail(file_, "node " + std::to_string(index) + " has more than one parent");
        if (depth > kMaxNodeDepth)
            fail(file_, "node " + std::to_string(index) + " is nested more than " +
                            std::to_string(kMaxNodeDepth) + " levels deep");
        onPath_[size_t(index)] = visited_[size_t(index)] = true;
        const tinygltf::Node& node = model_.nodes[size_t(index)];
        const glm::mat4 world = parent * localTransform(node, file_, index);
        // Each transform may be finite and their product still overflow.
        if (!finite(world))
            fail(file_, "node " + std::to_string(index) + ": world transform is not finite");
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model_.meshes.size())
                fail(file_, "node " + std::to_string(index) + " refers to mesh " +
                                std::to_string(node.mesh) + ", which does not exist");
            const auto& primitives = model_.meshes[size_t(node.mesh)].primitives;
            for (size_t p = 0; p < primitives.size(); ++p) {
                const int mesh = sceneMeshOf(node.mesh, int(p));
                if (mesh >= 0) scene_.instances.push_back({mesh, world, node.name});
            }
        }
        if (node.camera >= 0) noteCamera(node.camera, world);
        auto light = node.extensions.find("KHR_lights_punctual");
        if (light != node.extensions.end()) noteLight(light->second, world);
        for (int child : node.children)
            importNode(child, world, depth + 1);
        onPath_[size_t(index)] = false;
    }

    GltfViewpoint viewpoint() {
        GltfViewpoint result;
        result.camera = camera_;
        if (lightCount_ > 1)
            warnings_.once("glTF has " + std::to_string(lightCount_) +
                           " lights; only the first spot (else point) light is used");
        if (spot_) {
            result.light = spot_;
        } else if (point_) {
            warnings_.once("glTF point light is used as a spot light facing down (75 degree cone)");
            result.light = point_;
        }
        return result;
    }

private:
    // Scene mesh for a glTF (mesh, primitive), built on first use; -1 for skipped primitives.
    int sceneMeshOf(int gltfMesh, int primitiveIndex) {
        auto [cached, isNew] = meshOf_.try_emplace({gltfMesh, primitiveIndex}, -1);
        if (!isNew) return cached->second;
        const tinygltf::Primitive& primitive =
            model_.meshes[size_t(gltfMesh)].primitives[size_t(primitiveIndex)];
        const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            warnings_.once("glTF primitives of mode " + std::to_string(mode) +
                           " (points or lines) are skipped");
            return -1;
        }
        if (!primitive.targets.empty())
            warnings_.once("glTF morph targets are ignored: the base shape is drawn, without the "
                           "mesh's default morph weights");
        for (const auto& attribute : primitive.attributes)
            if (attribute.first.rfind("COLOR_", 0) == 0 && attribute.first != "COLOR_0")
                warnings_.once("glTF vertex colours other than COLOR_0 are ignored");
        const std::string where =
            "mesh " + std::to_string(gltfMesh) + " primitive " + std::to_string(primitiveIndex);
        Mesh mesh = buildPrimitiveMesh(model_, primitive, file_, where, warnings_);
        if (mesh.indices.empty()) return -1;
        mesh.material = materialOf(primitive.material, where);
        scene_.meshes.push_back(std::move(mesh));
        cached->second = int(scene_.meshes.size()) - 1;
        return cached->second;
    }

    int materialOf(int gltfMaterial, const std::string& where) {
        if (gltfMaterial >= int(model_.materials.size()))
            fail(file_, where + " refers to material " + std::to_string(gltfMaterial) +
                            ", which does not exist");
        if (gltfMaterial >= 0) return firstMaterial_ + gltfMaterial;
        // glTF's default material is white; 0.8 keeps energy conservation plausible.
        if (defaultMaterial_ < 0) {
            Material fallback;
            fallback.name = "default";
            fallback.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
            defaultMaterial_ = int(scene_.materials.size());
            scene_.materials.push_back(fallback);
        }
        return defaultMaterial_;
    }

    void noteCamera(int index, const glm::mat4& world) {
        if (size_t(index) >= model_.cameras.size())
            fail(file_, "camera " + std::to_string(index) + " does not exist");
        const tinygltf::Camera& source = model_.cameras[size_t(index)];
        if (source.type != "perspective") {
            warnings_.once("glTF " + source.type + " cameras are ignored");
            return;
        }
        if (camera_) return;
        const auto& p = source.perspective;
        if (!(p.yfov > 0.0 && p.yfov < 3.1) || !(p.znear > 0.0) || !(p.zfar >= 0.0))
            fail(file_, "camera " + std::to_string(index) + " has an invalid yfov/znear/zfar");
        if (p.yfov < glm::radians(double(kMinFovDegrees)))
            fail(file_, "camera " + std::to_string(index) + ": yfov " + std::to_string(p.yfov) +
                            " is narrower than " + std::to_string(kMinFovDegrees) + " degrees");
        // zfar 0 (absent) is an infinite projection, whose far plane is fitted to the scene.
        if (p.zfar > 0.0 && p.znear >= p.zfar)
            fail(file_, "camera " + std::to_string(index) + ": znear " + std::to_string(p.znear) +
                            " is not less than zfar " + std::to_string(p.zfar));
        Camera camera;
        camera.position = glm::vec3(world[3]);
        camera.orientation = orientationOf(world);
        camera.yfov = float(p.yfov);
        // Clip distances are lengths in the file's units, so they follow the load scale.
        camera.znear = float(p.znear) * scale_;
        camera.zfar = float(p.zfar) * scale_;
        // A node scaled to zero (or sheared flat) has no view direction.
        const glm::quat& q = camera.orientation;
        if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) ||
            !std::isfinite(q.z))
            fail(file_, "camera " + std::to_string(index) +
                            ": its node's transform has no view direction (zero scale?)");
        if (!std::isfinite(camera.znear) || !std::isfinite(camera.zfar))
            fail(file_, "camera " + std::to_string(index) + ": znear/zfar too large");
        camera_ = camera;
    }

    void noteLight(const tinygltf::Value& extension, const glm::mat4& world) {
        if (!extension.IsObject() || !extension.Get("light").IsNumber())
            fail(file_, "KHR_lights_punctual on a node needs a light index");
        // Checked as a double: converting 1e20 (or -1.5) to int first is undefined behaviour.
        const double number = extension.Get("light").GetNumberAsDouble();
        if (!(number >= 0.0 && number < double(model_.lights.size())) ||
            number != std::floor(number)) {
            std::ostringstream what;
            what << "light " << number << " does not exist";
            fail(file_, what.str());
        }
        const int index = int(number);
        const tinygltf::Light& source = model_.lights[size_t(index)];
        ++lightCount_;
        SpotLight light;
        light.position = glm::vec3(world[3]);
        light.direction = glm::normalize(glm::mat3(world) * glm::vec3(0, 0, -1));
        if (source.color.size() == 3)
            light.color = glm::vec3(source.color[0], source.color[1], source.color[2]);
        light.intensity = float(source.intensity);
        light.radius = 0.0f;
        const float maxOuter = glm::radians(89.0f);
        // Checked only for the light that is used: a broken light the scene ignores is harmless.
        auto check = [&](const char* type) {
            const std::string what = "light " + std::to_string(index) + " (" + type + ")";
            if (!finite(light.direction))
                fail(file_, what + ": its node's transform has no direction (zero scale?)");
            // The scene file's ranges: beyond them the light's radiance overflows a float.
            if (!(glm::all(glm::greaterThanEqual(light.color, glm::vec3(0.0f))) &&
                  glm::all(glm::lessThanEqual(light.color, glm::vec3(1e6f))) &&
                  light.intensity >= 0.0f && light.intensity <= 1e12f))
                fail(file_, what + ": color must be in [0, 1e6] and intensity in [0, 1e12]");
        };
        if (source.type == "spot" && !spot_) {
            check("spot");
            light.outerConeAngle = float(source.spot.outerConeAngle);
            if (!(light.outerConeAngle > 0.0f))
                fail(file_,
                     "light " + std::to_string(index) + " (spot): outerConeAngle must be > 0");
            if (light.outerConeAngle > maxOuter) {
                warnings_.once("glTF spot cone wider than 89 degrees is narrowed to 89");
                light.outerConeAngle = maxOuter;
            }
            light.innerConeAngle =
                std::clamp(float(source.spot.innerConeAngle), 0.0f, 0.99f * light.outerConeAngle);
            spot_ = light;
        } else if (source.type == "point" && !point_) {
            light.direction = glm::vec3(0, -1, 0); // a point light has none of its own
            check("point");
            light.outerConeAngle = glm::radians(75.0f);
            light.innerConeAngle = 0.0f;
            point_ = light;
        } else if (source.type == "directional") {
            warnings_.once("glTF directional lights are ignored");
        }
    }

    const tinygltf::Model& model_;
    const std::string& file_;
    float scale_;
    int firstMaterial_;
    Scene& scene_;
    GltfWarnings& warnings_;
    std::vector<bool> onPath_, visited_;
    std::map<std::pair<int, int>, int> meshOf_;
    int defaultMaterial_ = -1;
    int lightCount_ = 0;
    std::optional<Camera> camera_;
    std::optional<SpotLight> spot_, point_;
};

} // namespace

GltfViewpoint importNodes(const tinygltf::Model& model, const std::string& file, float scale,
                          int firstMaterial, Scene& scene, GltfWarnings& warnings) {
    NodeImporter importer(model, file, scale, firstMaterial, scene, warnings);
    const glm::mat4 root = glm::scale(glm::mat4(1.0f), glm::vec3(scale));
    if (model.scenes.empty()) {
        // No scene to pick: show every root node rather than nothing.
        std::vector<bool> isChild(model.nodes.size(), false);
        for (const auto& node : model.nodes)
            for (int child : node.children)
                if (child >= 0 && size_t(child) < isChild.size()) isChild[size_t(child)] = true;
        for (size_t n = 0; n < model.nodes.size(); ++n)
            if (!isChild[n]) importer.importNode(int(n), root);
        return importer.viewpoint();
    }
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(sceneIndex) >= model.scenes.size())
        fail(file, "default scene " + std::to_string(sceneIndex) + " does not exist");
    for (int node : model.scenes[size_t(sceneIndex)].nodes)
        importer.importNode(node, root);
    return importer.viewpoint();
}

} // namespace ssgi
