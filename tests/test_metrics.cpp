// The error metrics on synthetic images whose answers are known (the programs that use them,
// `compare` and `reference`, are test_ground_truth_programs.cpp's).
#include "metrics/comparison.h"
#include "metrics/error_map.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

using namespace ssgi;
using namespace ssgi::metrics;

namespace {

Image constant(uint32_t w, uint32_t h, float value) {
    return {w, h, std::vector<float>(size_t(w) * h * 4, value)};
}

// Smoothly varying colours with some structure, so SSIM has variance to compare.
Image pattern(uint32_t w, uint32_t h) {
    Image image = constant(w, h, 1.0f);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (size_t c = 0; c < 3; ++c)
                image.rgba[(size_t(y) * w + x) * 4 + c] =
                    0.5f + 0.4f * std::sin(0.3f * float(x) + float(c)) * std::cos(0.2f * float(y));
    return image;
}

TEST(Metrics, IdenticalImagesHaveNoErrorAndSsimOne) {
    const Image a = pattern(40, 30);
    const Figures f = errorFigures(a, a, Mask(), ssimMap(a, a));
    EXPECT_EQ(f.pixels, 1200u);
    EXPECT_EQ(f.relMse, 0.0);
    EXPECT_EQ(f.rmse, 0.0);
    EXPECT_EQ(f.mae, 0.0);
    EXPECT_NEAR(f.ssim, 1.0, 1e-12);
}

// Test 0.6 against reference 0.5 everywhere: RMSE = MAE = 0.1, relMSE = 0.01 / (0.25 + 0.01),
// and SSIM is its luminance term alone, (2 * 0.5 * 0.6 + C1) / (0.5^2 + 0.6^2 + C1), since
// neither image varies.
TEST(Metrics, ConstantOffsetGivesKnownFigures) {
    const Image reference = constant(16, 16, 0.5f), test = constant(16, 16, 0.6f);
    const Figures f = errorFigures(test, reference, Mask(), ssimMap(test, reference));
    EXPECT_NEAR(f.rmse, 0.1, 1e-6);
    EXPECT_NEAR(f.mae, 0.1, 1e-6);
    EXPECT_NEAR(f.relMse, 0.01 / 0.26, 1e-6);
    const double c1 = 1e-4;
    EXPECT_NEAR(f.ssim, (2 * 0.5 * 0.6 + c1) / (0.25 + 0.36 + c1), 1e-6);
}

TEST(Metrics, SsimFallsWhenStructureDiffers) {
    const Image a = pattern(32, 32);
    Image checker = constant(32, 32, 0.5f);
    for (size_t i = 0; i < checker.pixels(); ++i)
        for (size_t c = 0; c < 3; ++c)
            checker.rgba[4 * i + c] = ((i % 32) + (i / 32)) % 2 ? 0.9f : 0.1f;
    const Figures f = errorFigures(checker, a, Mask(), ssimMap(checker, a));
    EXPECT_LT(f.ssim, 0.2);
    EXPECT_GT(f.relMse, 0.05);
}

TEST(Metrics, EdgeBandCountsTheBorderPixels) {
    EXPECT_EQ(countInside(edgeBandMask(40, 30, 3)), 40u * 30u - 34u * 24u);
    EXPECT_EQ(countInside(edgeBandMask(40, 30, 1)), 2u * 40u + 2u * 28u);
    EXPECT_EQ(countInside(edgeBandMask(40, 30, 15)), 1200u) << "a band of half the height";
    EXPECT_EQ(countInside(edgeBandMask(40, 30, 0)), 0u);
    const Mask band = edgeBandMask(40, 30, 2);
    EXPECT_TRUE(band[0]);
    EXPECT_TRUE(band[size_t(29) * 40 + 38]);
    EXPECT_FALSE(band[size_t(2) * 40 + 2]);
}

// Errors only in the right half: a mask of the left half sees none, an empty region is NaN.
TEST(Metrics, MaskedFiguresCountOnlyTheirPixels) {
    const Image reference = constant(20, 10, 0.5f);
    Image test = reference, maskImage = constant(20, 10, 0.0f);
    for (uint32_t y = 0; y < 10; ++y)
        for (uint32_t x = 0; x < 20; ++x) {
            const size_t i = size_t(y) * 20 + x;
            if (x >= 10) test.rgba[4 * i] = 0.9f; // red channel only
            maskImage.rgba[4 * i] = x < 10 ? 1.0f : 0.2f;
        }
    const Mask left = thresholdMask(maskImage);
    EXPECT_EQ(countInside(left), 100u);
    const std::vector<double> ssim = ssimMap(test, reference);
    const Figures inside = errorFigures(test, reference, left, ssim);
    EXPECT_EQ(inside.pixels, 100u);
    EXPECT_EQ(inside.rmse, 0.0);
    const Figures whole = errorFigures(test, reference, Mask(), ssim);
    // Half the pixels, one channel of three, off by 0.4: mean squared error 0.16 / 6.
    EXPECT_NEAR(whole.rmse, std::sqrt(0.16 / 6.0), 1e-6);
    EXPECT_NEAR(whole.mae, 0.4 / 6.0, 1e-6);
    const Figures none = errorFigures(test, reference, Mask(200, 0), ssim);
    EXPECT_EQ(none.pixels, 0u);
    EXPECT_TRUE(std::isnan(none.relMse));
    EXPECT_THROW(errorFigures(constant(4, 4, 0), reference, Mask(), {}), std::invalid_argument);
}

TEST(Metrics, ErrorMapRunsDarkToLightWithTheError) {
    const Image reference = constant(4, 1, 0.5f);
    Image test = reference;
    const std::array<float, 4> offsets = {0.0f, 0.005f, 0.05f, 5.0f};
    for (size_t i = 0; i < 4; ++i)
        for (size_t c = 0; c < 3; ++c)
            test.rgba[4 * i + c] += offsets[i];
    const std::vector<float> map = errorMap(test, reference);
    float previous = -1.0f;
    for (size_t i = 0; i < 4; ++i) {
        const float lightness =
            0.2126f * map[4 * i] + 0.7152f * map[4 * i + 1] + 0.0722f * map[4 * i + 2];
        EXPECT_GT(lightness, previous) << "pixel " << i;
        previous = lightness;
    }
    EXPECT_EQ(glm::vec3(map[0], map[1], map[2]), errorColor(0.0)) << "no error is black";
    EXPECT_EQ(glm::vec3(map[12], map[13], map[14]), errorColor(1.0)) << "beyond 100%: the top";
    for (double t = 0.0; t < 1.0; t += 0.01) {
        const glm::vec3 a = errorColor(t), b = errorColor(t + 0.01);
        EXPECT_LT(0.2126f * a.r + 0.7152f * a.g + 0.0722f * a.b,
                  0.2126f * b.r + 0.7152f * b.g + 0.0722f * b.b)
            << "lightness must rise at t = " << t;
    }
}

} // namespace
