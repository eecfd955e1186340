// Error figures of a rendered image against a reference: relMSE, RMSE, mean absolute error and
// SSIM, over the whole image or inside a mask (disoccluded pixels, a screen-edge band, thin
// geometry).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ssgi::metrics {

// RGBA floats, rows top to bottom (what readImage returns).
struct Image {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
    size_t pixels() const { return size_t(width) * height; }
};

// One pixel per byte, nonzero = inside. An empty mask means every pixel.
using Mask = std::vector<uint8_t>;

// Figures over the pixels of a region; NaN when the region has no pixel.
struct Figures {
    size_t pixels = 0;
    double relMse = 0.0; // mean over pixels and RGB of (a - b)^2 / (b^2 + 0.01), b the reference
    double rmse = 0.0;   // sqrt of the mean over pixels and RGB of (a - b)^2
    double mae = 0.0;    // mean over pixels and RGB of |a - b|
    double ssim = 0.0;   // mean of the luminance SSIM map over the region's pixels
};

// The relMSE denominator's constant: keeps near-black reference pixels from dominating.
constexpr double kRelMseEpsilon = 0.01;

double luminance(const Image& image, size_t pixel);

// Per-pixel SSIM of the luminances (Wang et al. 2004): Gaussian window of sigma 1.5 pixels
// (11x11, renormalised where it overlaps the border), K1 = 0.01, K2 = 0.03, dynamic range 1
// (linear radiance of a well-exposed scene is mostly below 1).
std::vector<double> ssimMap(const Image& test, const Image& reference);

// Throws std::invalid_argument when the sizes differ (callers name the files).
Figures errorFigures(const Image& test, const Image& reference, const Mask& mask,
                     const std::vector<double>& ssim);

// The pixels within `band` pixels of the image border.
Mask edgeBandMask(uint32_t width, uint32_t height, uint32_t band);
// The pixels whose first channel is above 0.5 (a black-and-white mask image).
Mask thresholdMask(const Image& mask);
size_t countInside(const Mask& mask);

} // namespace ssgi::metrics
