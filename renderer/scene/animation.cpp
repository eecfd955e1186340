#include "scene/animation.h"

#include "scene/camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>

namespace ssgi {

void resolveObjectPaths(Scene& scene, const std::string& file) {
    for (size_t p = 0; p < scene.objectPaths.size(); ++p) {
        ObjectPath& path = scene.objectPaths[p];
        path.instances.clear();
        for (size_t i = 0; i < scene.instances.size(); ++i)
            if (!path.object.empty() && scene.instances[i].name == path.object)
                path.instances.push_back(int(i));
        if (path.instances.empty())
            throw InputError(file + ": 'object_paths[" + std::to_string(p) + "].object' is '" +
                             path.object + "', which names no object or glTF node");
        for (const ObjectKey& key : path.keys)
            for (int i : path.instances) {
                const Instance& instance = scene.instances[size_t(i)];
                const Aabb moved = instanceBounds(scene, size_t(i),
                                                  glm::translate(glm::mat4(1.0f), key.translation) *
                                                      instance.transform);
                scene.bounds.extend(moved.min);
                scene.bounds.extend(moved.max);
            }
    }
}

glm::vec3 translationAt(const ObjectPath& path, float time) {
    const std::vector<ObjectKey>& keys = path.keys;
    if (keys.empty()) return glm::vec3(0.0f);
    if (time <= keys.front().time) return keys.front().translation;
    if (time >= keys.back().time) return keys.back().translation;
    const auto next = std::upper_bound(keys.begin(), keys.end(), time,
                                       [](float t, const ObjectKey& k) { return t < k.time; });
    const ObjectKey& b = *next;
    const ObjectKey& a = *(next - 1);
    return glm::mix(a.translation, b.translation, (time - a.time) / (b.time - a.time));
}

std::vector<glm::mat4> instanceTransformsAt(const Scene& scene, float time) {
    std::vector<glm::mat4> transforms;
    for (const Instance& instance : scene.instances)
        transforms.push_back(instance.transform);
    for (const ObjectPath& path : scene.objectPaths) {
        const glm::mat4 move = glm::translate(glm::mat4(1.0f), translationAt(path, time));
        for (int i : path.instances)
            transforms[size_t(i)] = move * scene.instances[size_t(i)].transform;
    }
    return transforms;
}

Scene posedAt(const Scene& scene, float time) {
    Scene posed = scene;
    const std::vector<glm::mat4> transforms = instanceTransformsAt(scene, time);
    for (size_t i = 0; i < posed.instances.size(); ++i)
        posed.instances[i].transform = transforms[i];
    return posed;
}

Aabb instanceBounds(const Scene& scene, size_t instance, const glm::mat4& transform) {
    Aabb box;
    for (const Vertex& v : scene.meshes[size_t(scene.instances[instance].mesh)].vertices)
        box.extend(glm::vec3(transform * glm::vec4(v.position, 1.0f)));
    return box;
}

Camera cameraAtTime(const Scene& scene, float time, const std::string& sceneName) {
    if (scene.cameraPath.empty() && scene.objectPaths.empty())
        throw InputError(sceneName +
                         ": --time given but the scene has no camera_path or object_paths");
    return scene.cameraPath.empty() ? scene.camera : cameraAt(scene.cameraPath, time);
}

} // namespace ssgi
