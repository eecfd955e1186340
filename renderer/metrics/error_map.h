// A false-colour picture of where an image differs from its reference, for looking at errors
// rather than reading them: per-pixel relative error on a logarithmic scale.
#pragma once

#include "metrics/metrics.h"

#include <glm/glm.hpp>

namespace ssgi::metrics {

// Smallest and largest relative error the colours distinguish (below: black, above: white-ish).
constexpr double kErrorMapLow = 1e-3, kErrorMapHigh = 1.0;

// Per pixel: sqrt of the mean over RGB of (a - b)^2 / (b^2 + 0.01), the square root of the
// pixel's relMSE, so it reads as a relative error (0.1 = 10%).
std::vector<double> relativeErrorPerPixel(const Image& test, const Image& reference);

// t in [0, 1] -> display colour (sRGB-encoded). Lightness rises monotonically from black
// through purple, red and orange to pale yellow, so the order of errors reads without a legend
// and survives printing in grey.
glm::vec3 errorColor(double t);

// RGBA, ready for writeImage(.png): log10 of the relative error mapped from
// [kErrorMapLow, kErrorMapHigh] onto errorColor; non-finite values of `test` show as cyan.
std::vector<float> errorMap(const Image& test, const Image& reference);

} // namespace ssgi::metrics
