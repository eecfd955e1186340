// The timeline of timeline.h: the steps and where the last change falls.

#include "stability/timeline.h"

namespace ssgi::stability::detail {

bool sameLight(const SpotLight& a, const SpotLight& b) {
    return a.position == b.position && a.direction == b.direction;
}

bool sameStep(const Step& a, const Step& b, const Scene& scene) {
    return a.camera.position == b.camera.position && a.camera.orientation == b.camera.orientation &&
           sameLight(a.light, b.light) && a.width == b.width && a.height == b.height &&
           instanceTransformsAt(scene, a.time) == instanceTransformsAt(scene, b.time);
}

std::vector<Step> timeline(const Case& c, const Scene& scene, const RunOptions& o) {
    const CameraPath& path = scene.cameraPath;
    const float duration = path.keys.back().time - path.keys.front().time;
    const float start = path.keys.front().time;
    std::vector<Step> steps(
        o.warmup, {"warmup", cameraAt(path, start), scene.light, o.width, o.height, start});
    SpotLight light = scene.light;
    uint32_t width = o.width, height = o.height;
    const glm::vec3 finalDirection = glm::normalize(c.lightAim - c.lightTo);
    for (uint32_t p = 1; p <= c.pathFrames; ++p) {
        const float s = float(p) / float(c.pathFrames);
        if (c.movesLight) {
            light.position = glm::mix(scene.light.position, c.lightTo, s);
            light.direction = glm::normalize(glm::mix(scene.light.direction, finalDirection, s));
        }
        const float time = start + duration * s;
        steps.push_back({"path", cameraAt(path, time), light, width, height, time});
    }
    // A resize as the camera comes to rest: the hold's first frame is the new size, so the change
    // the case measures from is the resize alone.
    if (c.resizeScale > 0.0f) {
        width = std::max(1u, uint32_t(std::lround(o.width * c.resizeScale)));
        height = std::max(1u, uint32_t(std::lround(o.height * c.resizeScale)));
    }
    for (uint32_t i = 0; i < o.hold; ++i)
        steps.push_back({"hold", steps.back().camera, light, width, height, steps.back().time});
    return steps;
}

size_t indexOfLastChange(const std::vector<Step>& steps, const Scene& scene) {
    size_t last = 0;
    for (size_t i = 1; i < steps.size(); ++i)
        if (!sameStep(steps[i], steps[i - 1], scene)) last = i;
    return last;
}

} // namespace ssgi::stability::detail
