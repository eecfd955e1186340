// The scene description file (.json) as read and checked, before any glTF is loaded: every
// typo, wrong type and absurd number is reported without waiting for a large model to load.
#pragma once

#include "scene/scene.h"

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ssgi {

// Camera keys as written; what is absent comes from the camera this one refines.
struct CameraSpec {
    std::string where; // "camera" or "camera_path[2]", for messages
    std::optional<glm::vec3> position, target, direction, up;
    std::optional<float> yfovDegrees, znear, zfar;
    bool cut = false; // a camera path key that starts every history afresh
};

// Light keys as written; what is absent comes from the glTF light or the default light.
struct LightSpec {
    std::optional<glm::vec3> position, target, direction, color;
    std::optional<float> intensity, coneDegrees, innerConeDegrees, radius;
};

struct ObjectSpec {
    enum class Type { Quad, Box, Sphere } type = Type::Quad;
    std::string where;    // "objects[3]"
    std::string material; // a key of "materials"
    std::string name;
    std::array<glm::vec3, 4> corners{};
    glm::vec3 center{0.0f}, size{1.0f};
    float rotateYDegrees = 0.0f, radius = 1.0f;
    int segments = 32;
};

struct SceneDescription {
    std::vector<std::string> gltfPaths; // already relative to the working directory
    float gltfScale = 1.0f;
    std::vector<Material> materials; // Material::name is the key objects refer to
    std::vector<ObjectSpec> objects;
    std::optional<LightSpec> light;
    Sky sky;
    std::optional<CameraSpec> camera;
    std::vector<std::pair<float, CameraSpec>> cameraPath; // (time, key), sorted by time
    std::vector<ObjectPath> objectPaths;                  // instances not yet resolved
    SettingOverrides settings;                            // checked, not yet applied
};

// Reads and checks a scene file; InputError naming the file and the key on any problem.
SceneDescription readSceneDescription(const std::string& path);

} // namespace ssgi
