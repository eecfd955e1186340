// Golden-image checks look at what a user sees: the display image, 8 bits per channel. These
// turn any input into one and count the pixels that differ visibly (the test that Filament's
// render-diff CI applies: at most a fraction F of the pixels off by more than D of 255).
#pragma once

#include "metrics/metrics.h"

namespace ssgi::metrics {

// The display image of a file's pixels, quantised to 8 bits (k / 255). A display-encoded image
// (PNG) stays as it is; a linear one (EXR) goes through what the composite pass does: times
// `exposure`, Narkowicz's ACES fit, sRGB encoding. NaN stays NaN (so that it fails every check).
Image displayImage(const Image& image, bool linear, double exposure);

// One linear channel value through the composite's display transform (shader::tonemapAces and
// encodeSrgb in shared.h), in float as the shader computes it: times `exposure`, Narkowicz's
// ACES fit, sRGB encoding. Not quantised (reference --png and the Python module's tonemap()
// write or return it as it is).
float displayValue(float linear, float exposure);

// The fraction of pixels where any of R, G, B differs by more than `maxDiff` (0-255 units)
// between two display images; a pixel that is NaN in either counts as differing. Throws
// std::invalid_argument when the sizes differ.
double fractionDiffering(const Image& test, const Image& reference, double maxDiff);

} // namespace ssgi::metrics
