#include "support.h"

#include "renderer.h"

#include <array>
#include <cstdio>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>

#include <sys/wait.h>

namespace ssgi::test {

vk::Context& context() {
    static std::unique_ptr<vk::Context> ctx =
        std::make_unique<vk::Context>(vk::ContextOptions{/*validation=*/true, /*deviceName=*/""});
    return *ctx;
}

std::string sourcePath(const std::string& relative) {
    return std::string(SSGI_SOURCE_DIR) + "/" + relative;
}

std::string sceneModel(const std::string& name) {
    return std::string(SSGI_SOURCE_DIR) + "/scenes/models/" + name;
}

Scene scaledScene(Scene s, float k) {
    for (Instance& instance : s.instances)
        instance.transform = glm::scale(glm::mat4(1.0f), glm::vec3(k)) * instance.transform;
    s.bounds.min *= k, s.bounds.max *= k;
    s.light.position *= k, s.light.radius *= k, s.light.intensity *= k * k;
    s.camera.position *= k, s.camera.znear *= k, s.camera.zfar *= k;
    s.settings.ao_radius = aoRadius(s) * k;
    return s;
}

Frame render(const Scene& scene, uint32_t width, uint32_t height, uint32_t frames) {
    // The effects' raw outputs share memory with later passes' images: kept to be read.
    Renderer renderer(context(), scene,
                      {width, height, "final", {"direct", "ao", "indirect", "ssdo", "shadow"}});
    for (uint32_t i = 0; i < frames; ++i)
        renderer.renderFrame(scene.camera);
    Frame f;
    f.width = width;
    f.height = height;
    auto read = [&](const char* name) {
        return renderer.hasImage(name) ? renderer.readImage(name) : std::vector<float>();
    };
    f.direct = read("direct");
    f.position = read("gbuffer.position");
    f.normal = read("gbuffer.normal");
    f.albedo = read("gbuffer.albedo");
    f.hdr = read("hdr");
    f.ldr = read("ldr");
    f.ao = read("ao");
    f.indirect = read("indirect");
    f.ssdo = read("ssdo");
    f.shadow = read("shadow");
    return f;
}

// Möller-Trumbore: does the segment from `origin` to `target` cross any triangle of the scene?
bool segmentBlocked(const Scene& scene, glm::vec3 origin, glm::vec3 target) {
    const glm::vec3 d = target - origin;
    for (const Instance& inst : scene.instances) {
        const Mesh& mesh = scene.meshes[inst.mesh];
        const size_t count = mesh.indices.empty() ? mesh.vertices.size() : mesh.indices.size();
        for (size_t i = 0; i + 2 < count; i += 3) {
            glm::vec3 v[3];
            for (int k = 0; k < 3; ++k) {
                uint32_t idx = mesh.indices.empty() ? uint32_t(i + k) : mesh.indices[i + k];
                v[k] = glm::vec3(inst.transform * glm::vec4(mesh.vertices[idx].position, 1.0f));
            }
            glm::vec3 e1 = v[1] - v[0], e2 = v[2] - v[0];
            glm::vec3 p = glm::cross(d, e2);
            float det = glm::dot(e1, p);
            if (std::abs(det) < 1e-12f) continue;
            glm::vec3 s = origin - v[0];
            float u = glm::dot(s, p) / det;
            if (u < 0 || u > 1) continue;
            glm::vec3 q = glm::cross(s, e1);
            float w = glm::dot(d, q) / det;
            if (w < 0 || u + w > 1) continue;
            float t = glm::dot(e2, q) / det;
            if (t > 1e-4f && t < 1.0f - 1e-4f) return true;
        }
    }
    return false;
}

CommandResult runCommand(const std::string& command) {
    CommandResult r;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buffer;
    while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe))
        r.output.append(buffer.data(), n);
    const int status = pclose(pipe);
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

} // namespace ssgi::test
