#include "metrics/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ssgi::metrics {
namespace {

constexpr int kRadius = 5; // 11 taps
constexpr double kSigma = 1.5;

const std::array<double, 2 * kRadius + 1>& gaussianWeights() {
    static const auto weights = [] {
        std::array<double, 2 * kRadius + 1> w{};
        for (int i = -kRadius; i <= kRadius; ++i)
            w[size_t(i + kRadius)] = std::exp(-0.5 * i * i / (kSigma * kSigma));
        return w;
    }();
    return weights;
}

// Gaussian-weighted local mean of `values`, the window renormalised where it leaves the image
// so that border pixels are averages of what exists, not of zeros.
std::vector<double> blur(const std::vector<double>& values, uint32_t width, uint32_t height) {
    const auto& w = gaussianWeights();
    std::vector<double> rows(values.size()), out(values.size());
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            double sum = 0.0, weight = 0.0;
            for (int k = -kRadius; k <= kRadius; ++k) {
                const long xx = long(x) + k;
                if (xx < 0 || xx >= long(width)) continue;
                sum += w[size_t(k + kRadius)] * values[size_t(y) * width + size_t(xx)];
                weight += w[size_t(k + kRadius)];
            }
            rows[size_t(y) * width + x] = sum / weight;
        }
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            double sum = 0.0, weight = 0.0;
            for (int k = -kRadius; k <= kRadius; ++k) {
                const long yy = long(y) + k;
                if (yy < 0 || yy >= long(height)) continue;
                sum += w[size_t(k + kRadius)] * rows[size_t(yy) * width + x];
                weight += w[size_t(k + kRadius)];
            }
            out[size_t(y) * width + x] = sum / weight;
        }
    return out;
}

void requireSameSize(const Image& test, const Image& reference) {
    if (test.width != reference.width || test.height != reference.height)
        throw std::invalid_argument("image sizes differ: " + std::to_string(test.width) + "x" +
                                    std::to_string(test.height) + " against " +
                                    std::to_string(reference.width) + "x" +
                                    std::to_string(reference.height));
    if (test.rgba.size() < test.pixels() * 4 || reference.rgba.size() < reference.pixels() * 4)
        throw std::invalid_argument("an image holds fewer than width x height RGBA pixels");
}

} // namespace

double luminance(const Image& image, size_t pixel) {
    const float* p = &image.rgba[4 * pixel];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

std::vector<double> ssimMap(const Image& test, const Image& reference) {
    requireSameSize(test, reference);
    const size_t n = test.pixels();
    std::vector<double> x(n), y(n), xx(n), yy(n), xy(n);
    for (size_t i = 0; i < n; ++i) {
        x[i] = luminance(test, i);
        y[i] = luminance(reference, i);
        xx[i] = x[i] * x[i];
        yy[i] = y[i] * y[i];
        xy[i] = x[i] * y[i];
    }
    const uint32_t w = test.width, h = test.height;
    const auto mx = blur(x, w, h), my = blur(y, w, h);
    const auto sxx = blur(xx, w, h), syy = blur(yy, w, h), sxy = blur(xy, w, h);
    constexpr double c1 = (0.01 * 1.0) * (0.01 * 1.0), c2 = (0.03 * 1.0) * (0.03 * 1.0);
    std::vector<double> ssim(n);
    for (size_t i = 0; i < n; ++i) {
        const double varX = sxx[i] - mx[i] * mx[i], varY = syy[i] - my[i] * my[i];
        const double cov = sxy[i] - mx[i] * my[i];
        ssim[i] = ((2.0 * mx[i] * my[i] + c1) * (2.0 * cov + c2)) /
                  ((mx[i] * mx[i] + my[i] * my[i] + c1) * (varX + varY + c2));
    }
    return ssim;
}

Figures errorFigures(const Image& test, const Image& reference, const Mask& mask,
                     const std::vector<double>& ssim) {
    requireSameSize(test, reference);
    if (!mask.empty() && mask.size() != test.pixels())
        throw std::invalid_argument("the mask's size differs from the images'");
    Figures f;
    double relSum = 0.0, squaredSum = 0.0, absoluteSum = 0.0, ssimSum = 0.0;
    for (size_t i = 0; i < test.pixels(); ++i) {
        if (!mask.empty() && !mask[i]) continue;
        ++f.pixels;
        for (int c = 0; c < 3; ++c) {
            const double a = test.rgba[4 * i + size_t(c)], b = reference.rgba[4 * i + size_t(c)];
            relSum += (a - b) * (a - b) / (b * b + kRelMseEpsilon);
            squaredSum += (a - b) * (a - b);
            absoluteSum += std::abs(a - b);
        }
        if (i < ssim.size()) ssimSum += ssim[i];
    }
    if (f.pixels == 0) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        f.relMse = f.rmse = f.mae = f.ssim = nan;
        return f;
    }
    const double values = 3.0 * double(f.pixels);
    f.relMse = relSum / values;
    f.rmse = std::sqrt(squaredSum / values);
    f.mae = absoluteSum / values;
    f.ssim = ssim.size() == test.pixels() ? ssimSum / double(f.pixels)
                                          : std::numeric_limits<double>::quiet_NaN();
    return f;
}

Mask edgeBandMask(uint32_t width, uint32_t height, uint32_t band) {
    Mask mask(size_t(width) * height, 0);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const uint32_t nearest = std::min({x, y, width - 1 - x, height - 1 - y});
            mask[size_t(y) * width + x] = nearest < band ? 1 : 0;
        }
    return mask;
}

Mask thresholdMask(const Image& mask) {
    Mask result(mask.pixels());
    for (size_t i = 0; i < mask.pixels(); ++i)
        result[i] = mask.rgba[4 * i] > 0.5f ? 1 : 0;
    return result;
}

size_t countInside(const Mask& mask) {
    return size_t(std::count_if(mask.begin(), mask.end(), [](uint8_t m) { return m != 0; }));
}

} // namespace ssgi::metrics
