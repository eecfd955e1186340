// What the reference computes, one estimator per mode; each mode is the same quantity as one
// real-time effect, so the two can be compared pixel by pixel.
#pragma once

#include "reference/random.h"
#include "reference/ray_scene.h"

#include <string>
#include <vector>

namespace ssgi::reference {

enum class Mode {
    Direct,   // radiance from the spot light alone (soft shadows from its disk)
    Ao,       // cosine-weighted visibility within aoRadius(scene), 1 = open, background 0
    Indirect, // radiance of spot light reflected exactly once before the visible surface
    Full,     // direct + that one bounce + sky light on the visible surface + the sky itself
    Multi,    // every bounce of spot and sky light (Russian roulette), for information
    Sky, // the sky's light alone on the visible surface, with visibility (no bounce), + the sky
};

const std::vector<std::string>& modeNames();
// Throws InputError naming `option` and the valid names.
Mode parseMode(const std::string& name, const std::string& option = "--mode");
const char* modeName(Mode mode);

class Integrator {
public:
    Integrator(const Scene& scene, const RayScene& rays, Mode mode);

    // One sample for a camera ray: rgb = radiance (AO: visibility as grey), a = 1 where the
    // ray found a surface. The ray covers [0, tfar) of origin + t * direction.
    glm::vec4 cameraSample(glm::vec3 origin, glm::vec3 direction, float tfar, Rng& rng) const;

    // One-sample estimate of the irradiance at `surface` (its normal) from the light this
    // mode counts, as if it were a white diffuse surface; AO mode: the visibility.
    glm::vec3 irradianceSample(const Surface& surface, Rng& rng) const;

    // Whether every sample of a camera ray gives the same value: the direct light of a point
    // light, which draws no random number.
    bool drawsNoRandomNumber() const;

private:
    // Radiance leaving `surface` toward where the ray came from, from the light this mode
    // counts.
    glm::vec3 outgoing(Surface surface, Rng& rng) const;
    float visibility(const Surface& surface, Rng& rng) const;

    // Which path vertices gather the spot light and which escaping rays see the sky; vertex 0
    // is the visible surface, and sky index -1 is the camera ray itself.
    struct Terms {
        int firstSpot, lastSpot, firstSky, lastSky, lastVertex;
        bool roulette;
    };

    const Scene& scene_;
    const RayScene& rays_;
    Mode mode_;
    Terms terms_;
    float aoRadius_;
};

// Irradiance at `point` with unit `normal` (AO mode: visibility), averaged over `samples`
// samples of the seeded streams; for tests against closed-form answers.
glm::vec3 estimateIrradiance(const Scene& scene, const RayScene& rays, Mode mode, glm::vec3 point,
                             glm::vec3 normal, uint32_t samples, uint64_t seed = 1);

} // namespace ssgi::reference
