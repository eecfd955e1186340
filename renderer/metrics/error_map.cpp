#include "metrics/error_map.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace ssgi::metrics {

std::vector<double> relativeErrorPerPixel(const Image& test, const Image& reference) {
    std::vector<double> error(test.pixels());
    for (size_t i = 0; i < test.pixels(); ++i) {
        double sum = 0.0;
        for (size_t c = 0; c < 3; ++c) {
            const double a = test.rgba[4 * i + c], b = reference.rgba[4 * i + c];
            sum += (a - b) * (a - b) / (b * b + kRelMseEpsilon);
        }
        error[i] = std::sqrt(sum / 3.0);
    }
    return error;
}

glm::vec3 errorColor(double t) {
    // Control points chosen by lightness: each is lighter than the one before.
    static const std::array<glm::vec3, 6> ramp = {
        glm::vec3(0.00f, 0.00f, 0.02f), glm::vec3(0.20f, 0.05f, 0.45f),
        glm::vec3(0.55f, 0.10f, 0.50f), glm::vec3(0.88f, 0.28f, 0.25f),
        glm::vec3(0.98f, 0.62f, 0.10f), glm::vec3(0.99f, 0.97f, 0.72f),
    };
    if (!(t > 0.0)) return ramp.front();
    const double x = std::min(t, 1.0) * double(ramp.size() - 1);
    const size_t i = std::min(size_t(x), ramp.size() - 2);
    return glm::mix(ramp[i], ramp[i + 1], float(x - double(i)));
}

std::vector<float> errorMap(const Image& test, const Image& reference) {
    const std::vector<double> error = relativeErrorPerPixel(test, reference);
    const double low = std::log10(kErrorMapLow), high = std::log10(kErrorMapHigh);
    std::vector<float> rgba(test.pixels() * 4, 1.0f);
    for (size_t i = 0; i < error.size(); ++i) {
        glm::vec3 color(0.0f, 1.0f, 1.0f);
        if (std::isfinite(error[i])) {
            const double t = error[i] > 0.0 ? (std::log10(error[i]) - low) / (high - low) : 0.0;
            color = errorColor(std::clamp(t, 0.0, 1.0));
        }
        rgba[4 * i + 0] = color.r;
        rgba[4 * i + 1] = color.g;
        rgba[4 * i + 2] = color.b;
    }
    return rgba;
}

} // namespace ssgi::metrics
