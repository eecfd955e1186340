#include "metrics/golden.h"

#include "shared.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ssgi::metrics {

Image displayImage(const Image& image, bool linear, double exposure) {
    Image out = image;
    for (size_t i = 0; i < image.pixels(); ++i)
        for (size_t c = 0; c < 3; ++c) {
            double v = image.rgba[4 * i + c];
            if (linear) // the composite's display transform; NaN stays NaN
                v = shader::encodeSrgb(shader::tonemapAces(float(v * exposure)));
            // What an 8-bit PNG of it would hold; a PNG read back is already on this grid.
            out.rgba[4 * i + c] = std::isnan(v)
                                      ? float(v)
                                      : float(std::round(std::clamp(v, 0.0, 1.0) * 255.0) / 255.0);
        }
    return out;
}

float displayValue(float linear, float exposure) {
    return shader::encodeSrgb(shader::tonemapAces(linear * exposure));
}

double fractionDiffering(const Image& test, const Image& reference, double maxDiff) {
    if (test.width != reference.width || test.height != reference.height)
        throw std::invalid_argument("image sizes differ");
    if (test.pixels() == 0) return 0.0;
    size_t differing = 0;
    for (size_t i = 0; i < test.pixels(); ++i) {
        bool differs = false;
        for (size_t c = 0; c < 3; ++c) {
            // Whole 0-255 steps, so that D = 5 means "6 or more" with no float rounding doubt.
            const double a = std::round(double(test.rgba[4 * i + c]) * 255.0);
            const double b = std::round(double(reference.rgba[4 * i + c]) * 255.0);
            differs = differs || !(std::abs(a - b) <= maxDiff);
        }
        differing += differs;
    }
    return double(differing) / double(test.pixels());
}

} // namespace ssgi::metrics
