#include "reference/integrator.h"

#include "reference/lighting.h"

#include <algorithm>
#include <climits>
#include <limits>

namespace ssgi::reference {
namespace {

constexpr float kPi = 3.14159265358979f;
// A path this long carries less than 0.95^60 of its light even with white walls; the cap only
// guards against a pathological loop.
constexpr int kMaxVertices = 256;
// Bounces before Russian roulette may end a path: the first ones carry most of the light.
constexpr int kRouletteFrom = 3;

} // namespace

const std::vector<std::string>& modeNames() {
    static const std::vector<std::string> names = {"direct", "ao",    "indirect",
                                                   "full",   "multi", "sky"};
    return names;
}

Mode parseMode(const std::string& name, const std::string& option) {
    const auto& names = modeNames();
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end())
        throw InputError(option + ": '" + name +
                         "' is not a mode (direct, ao, indirect, full, multi, sky)");
    return Mode(it - names.begin());
}

const char* modeName(Mode mode) {
    return modeNames()[size_t(mode)].c_str();
}

Integrator::Integrator(const Scene& scene, const RayScene& rays, Mode mode)
    : scene_(scene), rays_(rays), mode_(mode), aoRadius_(aoRadius(scene)) {
    switch (mode) {
    case Mode::Direct:
        terms_ = {0, 0, 1, 0, 0, false};
        break;
    case Mode::Indirect:
        terms_ = {1, 1, 1, 0, 1, false};
        break;
    case Mode::Full:
        terms_ = {0, 1, -1, 0, 1, false};
        break;
    case Mode::Multi:
        terms_ = {0, INT_MAX, -1, INT_MAX, kMaxVertices, true};
        break;
    case Mode::Ao:
        terms_ = {1, 0, 1, 0, 0, false};
        break;
    case Mode::Sky: // no spot light; the camera ray's sky and the sky seen from the surface
        terms_ = {1, 0, -1, 0, 1, false};
        break;
    }
}

glm::vec4 Integrator::cameraSample(glm::vec3 origin, glm::vec3 direction, float tfar,
                                   Rng& rng) const {
    Surface surface;
    if (!rays_.intersect(origin, direction, tfar, surface)) {
        const bool seesSky = terms_.firstSky <= -1 && -1 <= terms_.lastSky;
        return glm::vec4(seesSky ? skyRadiance(scene_.sky, direction) : glm::vec3(0.0f), 0.0f);
    }
    if (mode_ == Mode::Ao) return glm::vec4(glm::vec3(visibility(surface, rng)), 1.0f);
    return glm::vec4(outgoing(surface, rng), 1.0f);
}

glm::vec3 Integrator::irradianceSample(const Surface& surface, Rng& rng) const {
    if (mode_ == Mode::Ao) return glm::vec3(visibility(surface, rng));
    Surface white = surface;
    white.albedo = glm::vec3(1.0f);
    // A white Lambertian surface reflects radiance E / pi.
    return kPi * outgoing(white, rng);
}

bool Integrator::drawsNoRandomNumber() const {
    return mode_ == Mode::Direct && !(scene_.light.radius > 0.0f);
}

glm::vec3 Integrator::outgoing(Surface surface, Rng& rng) const {
    glm::vec3 radiance(0.0f), throughput(1.0f);
    for (int vertex = 0;; ++vertex) {
        if (terms_.firstSpot <= vertex && vertex <= terms_.lastSpot)
            radiance += throughput * surface.albedo / kPi *
                        spotIrradiance(rays_, scene_.light, surface, rng);
        if (vertex >= terms_.lastVertex) break;
        // Cosine-weighted sampling: BRDF * cos / pdf = (albedo/pi) cos / (cos/pi) = albedo.
        throughput *= surface.albedo;
        if (terms_.roulette && vertex >= kRouletteFrom) {
            const float keep =
                std::min(0.95f, std::max({throughput.r, throughput.g, throughput.b}));
            if (keep <= 0.0f || rng.uniform() >= keep) break;
            throughput /= keep;
        }
        if (throughput == glm::vec3(0.0f)) break;
        const glm::vec3 direction = cosineHemisphere(surface.normal, rng.uniform2());
        // Below the triangle's own plane (a smooth normal tilted away from it): the ray would
        // enter the surface it leaves.
        if (glm::dot(direction, surface.geometricNormal) <= 0.0f) break;
        const glm::vec3 origin = rays_.rayOrigin(surface, direction);
        Surface next;
        if (!rays_.intersect(origin, direction, std::numeric_limits<float>::infinity(), next)) {
            if (terms_.firstSky <= vertex && vertex <= terms_.lastSky)
                radiance += throughput * skyRadiance(scene_.sky, direction);
            break;
        }
        surface = next;
    }
    return radiance;
}

float Integrator::visibility(const Surface& surface, Rng& rng) const {
    const glm::vec3 direction = cosineHemisphere(surface.normal, rng.uniform2());
    if (glm::dot(direction, surface.geometricNormal) <= 0.0f) return 0.0f;
    const glm::vec3 origin = rays_.rayOrigin(surface, direction);
    return rays_.occluded(origin, direction, aoRadius_) ? 0.0f : 1.0f;
}

glm::vec3 estimateIrradiance(const Scene& scene, const RayScene& rays, Mode mode, glm::vec3 point,
                             glm::vec3 normal, uint32_t samples, uint64_t seed) {
    const Integrator integrator(scene, rays, mode);
    Surface surface;
    surface.position = point;
    surface.normal = surface.geometricNormal = glm::normalize(normal);
    glm::dvec3 sum(0.0);
    for (uint32_t s = 0; s < samples; ++s) {
        Rng rng(seed, 0, s);
        sum += glm::dvec3(integrator.irradianceSample(surface, rng));
    }
    return glm::vec3(sum / double(std::max(samples, 1u)));
}

} // namespace ssgi::reference
