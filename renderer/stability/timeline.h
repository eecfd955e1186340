// A case's timeline, frame by frame: a still warm-up, the camera (and light) path, a still hold
// at the final size.
#pragma once

#include "stability/run.h"

namespace ssgi::stability::detail {

// What one frame of the timeline renders.
struct Step {
    const char* phase;
    Camera camera;
    SpotLight light;
    uint32_t width, height;
    float time; // along the camera and object paths
};

bool sameLight(const SpotLight& a, const SpotLight& b);

// The same camera, light, size and object poses.
bool sameStep(const Step& a, const Step& b, const Scene& scene);

std::vector<Step> timeline(const Case& c, const Scene& scene, const RunOptions& o);

// The index of the last step that differs from the one before it; 0 where none does.
size_t indexOfLastChange(const std::vector<Step>& steps, const Scene& scene);

} // namespace ssgi::stability::detail
