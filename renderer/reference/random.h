// Counter-based random numbers for the path tracer: every (pixel, sample) pair owns its own
// stream derived by hashing, so an image depends only on the seed and the options, never on
// which thread rendered which pixel or in what order.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace ssgi::reference {

// A 64-bit finaliser (the splitmix64 output function): every input bit affects every output
// bit, which is what turns consecutive counters into independent-looking numbers.
inline uint64_t mix64(uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}

class Rng {
public:
    Rng(uint64_t seed, uint64_t pixel, uint64_t sample)
        : key_(mix64(mix64(mix64(seed + 0x9e3779b97f4a7c15ull) ^ pixel) ^ sample)) {}

    // Uniform in [0, 1): the top 24 bits, so the result is exactly representable and < 1.
    float uniform() {
        return float(mix64(key_ + 0x9e3779b97f4a7c15ull * ++counter_) >> 40) * 0x1p-24f;
    }
    glm::vec2 uniform2() {
        const float a = uniform();
        return {a, uniform()};
    }

private:
    uint64_t key_;
    uint64_t counter_ = 0;
};

// Two unit vectors completing `n` to a right-handed orthonormal basis, without a branch that
// flips near the poles (Duff et al. 2017, "Building an orthonormal basis, revisited").
inline void orthonormalBasis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

// A point on the unit disk, uniform by area.
inline glm::vec2 uniformDisk(glm::vec2 u) {
    const float r = std::sqrt(u.x);
    const float phi = 6.28318530718f * u.y;
    return {r * std::cos(phi), r * std::sin(phi)};
}

// A direction about `n` with density cos(theta)/pi: a uniform disk point lifted onto the
// hemisphere (Malley's method).
inline glm::vec3 cosineHemisphere(const glm::vec3& n, glm::vec2 u) {
    const glm::vec2 d = uniformDisk(u);
    const float z = std::sqrt(std::max(0.0f, 1.0f - glm::dot(d, d)));
    glm::vec3 t, b;
    orthonormalBasis(n, t, b);
    return glm::normalize(d.x * t + d.y * b + z * n);
}

} // namespace ssgi::reference
