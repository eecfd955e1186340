// LDR-FLIP against values worked out by hand, the golden-image difference count, and the
// thresholds of `compare` as CI runs it (exit 1 when one is exceeded, 0 when all pass, 2 for bad
// input).
#include "image_io.h"
#include "metrics/flip.h"
#include "metrics/golden.h"
#include "support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace ssgi;
using namespace ssgi::metrics;

namespace {

Image constant(uint32_t w, uint32_t h, float value) {
    return {w, h, std::vector<float>(size_t(w) * h * 4, value)};
}

// Structure at several scales and colours, so that both the colour and the feature pipelines
// see something.
Image pattern(uint32_t w, uint32_t h, int shift = 0) {
    Image image = constant(w, h, 1.0f);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (size_t c = 0; c < 3; ++c) {
                const float u = float(int(x) + shift);
                image.rgba[(size_t(y) * w + x) * 4 + c] =
                    0.5f + 0.45f * std::sin(0.7f * u + 1.3f * float(c)) * std::cos(0.4f * float(y));
            }
    return image;
}

TEST(Flip, ImageAgainstItselfIsExactlyZero) {
    const Image a = pattern(48, 40);
    const flip::Result r = flip::flip(a, a);
    EXPECT_EQ(r.mean, 0.0);
    for (double v : r.map)
        ASSERT_EQ(v, 0.0);
}

TEST(Flip, OnePixelShiftIsVisible) {
    const flip::Result r = flip::flip(pattern(48, 40, 1), pattern(48, 40));
    EXPECT_GT(r.mean, 0.01);
    EXPECT_LE(r.mean, 1.0);
}

// White is the reference white: Y = 116 * 1 - 16 = 100, no chroma. sRGB 0.5 is linear
// ((0.5 + 0.055) / 1.055)^2.4 = 0.214041, so Y = 116 * 0.214041 - 16 = 8.82877; grey has no
// chroma either. Both go back to linear unchanged.
TEST(Flip, YcxczOfWhiteAndMidGrey) {
    const glm::dvec3 white = flip::ycxczFromLinear(glm::dvec3(1.0));
    EXPECT_NEAR(white.x, 100.0, 1e-9);
    EXPECT_NEAR(white.y, 0.0, 1e-9);
    EXPECT_NEAR(white.z, 0.0, 1e-9);
    const glm::dvec3 linearGrey = flip::linearFromSrgb(glm::dvec3(0.5));
    EXPECT_NEAR(linearGrey.x, 0.214041, 1e-6);
    const glm::dvec3 grey = flip::ycxczFromLinear(linearGrey);
    EXPECT_NEAR(grey.x, 8.82877, 1e-4);
    EXPECT_NEAR(grey.y, 0.0, 1e-9);
    EXPECT_NEAR(grey.z, 0.0, 1e-9);
    const glm::dvec3 back = flip::linearFromYcxcz(grey);
    EXPECT_NEAR(back.r, 0.214041, 1e-6);
    EXPECT_NEAR(back.b, 0.214041, 1e-6);
    EXPECT_NEAR(flip::labFromLinear(glm::dvec3(1.0)).x, 100.0, 1e-9);
}

// |50 - 40| + sqrt((10 - 13)^2 + (-20 + 16)^2) = 10 + 5. Hunt: (50, 10, -20) -> (50, 5, -10).
TEST(Flip, HyabAndHunt) {
    EXPECT_DOUBLE_EQ(flip::hyab({50.0, 10.0, -20.0}, {40.0, 13.0, -16.0}), 15.0);
    const glm::dvec3 h = flip::hunt({50.0, 10.0, -20.0});
    EXPECT_DOUBLE_EQ(h.y, 5.0);
    EXPECT_DOUBLE_EQ(h.z, -10.0);
}

// Green (0, 1, 0): L*a*b* (87.73, -86.18, 83.18), Hunt (87.73, -75.61, 72.98); blue (0, 0, 1):
// (32.30, 79.19, -107.86), Hunt (32.30, 25.58, -34.84). HyAB = 55.44 + sqrt(101.19^2 +
// 107.81^2) = 55.44 + 147.86 = 203.30, so c_max = 203.30^0.7 = 41.275. At the cutoff,
// d^0.7 = 0.4 c_max, the colour error is p_t = 0.95 from both sides; green against blue is 1.
TEST(Flip, ColourErrorRedistribution) {
    EXPECT_NEAR(flip::maxColorError(), 41.275, 1e-3);
    const double cutoff = std::pow(flip::kPc * flip::maxColorError(), 1.0 / flip::kQc);
    EXPECT_NEAR(flip::redistributeColorError(cutoff), flip::kPt, 1e-12);
    EXPECT_NEAR(flip::redistributeColorError(cutoff * (1.0 - 1e-9)), flip::kPt, 1e-6);
    EXPECT_NEAR(flip::redistributeColorError(203.297), 1.0, 1e-4);
    EXPECT_EQ(flip::redistributeColorError(0.0), 0.0);
    // Below the cutoff it is linear in d^0.7: half of it gives half of p_t.
    EXPECT_NEAR(flip::redistributeColorError(cutoff * std::pow(0.5, 1.0 / flip::kQc)),
                0.5 * flip::kPt, 1e-12);
}

// 3 sigma of the widest CSF Gaussian: 3 sqrt(0.04 / (2 pi^2)) 67 = 9.05 -> 10 pixels.
// Feature error: (max(|0.5 - 0.1|, 0) / sqrt 2)^0.5 = 0.28284^0.5 = 0.53183.
TEST(Flip, CsfRadiusAndFeatureError) {
    EXPECT_EQ(flip::csfRadius(67.0), 10);
    EXPECT_NEAR(flip::featureError(0.5, 0.1, 0.2, 0.2), 0.531830, 1e-6);
    EXPECT_NEAR(flip::featureError(0.0, 0.0, 0.3, 0.7), std::pow(0.4 / std::sqrt(2.0), 0.5), 1e-12);
}

// Two flat fields: the CSF filters sum to 1 and the feature detectors see nothing, so every
// pixel's FLIP is the colour error of the two colours alone. (Not to 1e-12: the derivative
// filters' weights cancel only to rounding, ~1e-17, and the feature error's square root lifts
// that to ~1e-9.)
TEST(Flip, FlatFieldsGiveTheColourErrorAlone) {
    const Image a = constant(24, 20, 0.5f), b = constant(24, 20, 0.6f);
    const auto lab = [](double v) {
        return flip::hunt(flip::labFromLinear(flip::linearFromSrgb(glm::dvec3(v))));
    };
    const double expected = flip::redistributeColorError(flip::hyab(lab(0.5f), lab(0.6f)));
    const flip::Result r = flip::flip(a, b);
    EXPECT_GT(expected, 0.0);
    EXPECT_NEAR(r.mean, expected, 1e-7);
    EXPECT_NEAR(r.map.front(), expected, 1e-7);
    EXPECT_THROW(flip::flip(a, constant(4, 4, 0.5f)), std::invalid_argument);
}

TEST(Golden, CountsPixelsOffByMoreThanD) {
    Image reference = constant(10, 10, 100.0f / 255.0f), test = reference;
    test.rgba[0] = 106.0f / 255.0f;        // pixel 0: off by 6 in red
    test.rgba[4 * 1 + 2] = 95.0f / 255.0f; // pixel 1: off by 5 in blue
    test.rgba[4 * 2 + 1] = std::nanf("");  // pixel 2: NaN always differs
    EXPECT_DOUBLE_EQ(fractionDiffering(test, reference, 5.0), 0.02);
    EXPECT_DOUBLE_EQ(fractionDiffering(test, reference, 4.0), 0.03);
    // A linear 0.18 through ACES and sRGB lands on the 8-bit grid.
    const Image shown = displayImage(constant(1, 1, 0.18f), true, 1.0);
    EXPECT_FLOAT_EQ(shown.rgba[0] * 255.0f, std::round(shown.rgba[0] * 255.0f));
    EXPECT_GT(shown.rgba[0], 0.3f);
    EXPECT_EQ(displayImage(test, false, 1.0).rgba[0], test.rgba[0]) << "a PNG stays as stored";
}

// compare as CI runs it; the binary sits beside the tests' folder in the build tree.
class Thresholds : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("ssgi-flip-" + std::to_string(getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        // 4 of 1024 pixels brighter by 0.2 (51 of 255) in every channel.
        Image changed = pattern(32, 32);
        for (size_t i : {100u, 101u, 500u, 900u})
            for (size_t c = 0; c < 3; ++c)
                changed.rgba[4 * i + c] += 0.2f;
        reference = write("reference.png", pattern(32, 32));
        test = write("test.png", changed);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string write(const std::string& name, const Image& image) {
        writeImage((dir / name).string(), image.width, image.height, image.rgba);
        return (dir / name).string();
    }
    int compare(const std::string& options) {
        const fs::path binary =
            fs::read_symlink("/proc/self/exe").parent_path().parent_path() / "compare";
        if (!fs::exists(binary)) ADD_FAILURE() << binary << " is not built";
        const test::CommandResult r =
            test::runCommand(binary.string() + " " + test + " " + reference + " " + options);
        output = r.output;
        return r.status;
    }
    fs::path dir;
    std::string reference, test, output;
};

TEST_F(Thresholds, RelMse) {
    EXPECT_EQ(compare("--max-relmse 1e-5"), 1) << output;
    EXPECT_NE(output.find("FAIL: relMSE"), std::string::npos) << output;
    EXPECT_EQ(compare("--max-relmse 0.1"), 0) << output;
    EXPECT_NE(output.find("PASS: relMSE"), std::string::npos) << output;
}

TEST_F(Thresholds, MaxDiffAndFraction) {
    EXPECT_EQ(compare("--max-diff 5 --max-fraction 0.001"), 1) << output; // 4/1024 = 0.0039
    EXPECT_NE(output.find("FAIL: fraction of pixels off by more than 5/255 0.003906 > 0.001"),
              std::string::npos)
        << output;
    EXPECT_EQ(compare("--max-diff 5 --max-fraction 0.005"), 0) << output;
    EXPECT_EQ(compare("--max-diff 56"), 0) << output << "off by 51 at most";
    EXPECT_EQ(compare("--max-diff 45"), 1) << output << "no fraction given: no pixel may differ";
}

TEST_F(Thresholds, MeanFlipAndItsMap) {
    const std::string map = (dir / "flip.png").string();
    EXPECT_EQ(compare("--max-flip 1e-4 --flip-map " + map), 1) << output;
    EXPECT_NE(output.find("FAIL: mean FLIP"), std::string::npos) << output;
    EXPECT_EQ(compare("--max-flip 0.2"), 0) << output;
    uint32_t w = 0, h = 0;
    const std::vector<float> pixels = readImage(map, w, h);
    ASSERT_EQ(w * h, 32u * 32u);
    EXPECT_GT(pixels[4 * 100], pixels[4 * 700]) << "the changed pixel is brighter on the map";
    // Linear EXR inputs are tonemapped first; against itself every check passes.
    const std::string exr = write("linear.exr", pattern(32, 32));
    test = reference = exr;
    EXPECT_EQ(compare("--max-flip 0 --max-diff 0 --max-relmse 0"), 0) << output;
}

TEST_F(Thresholds, BadInputIsExitTwo) {
    for (const std::string options :
         {"--max-relmse -1", "--max-relmse abc", "--max-fraction 1.5 --max-diff 5",
          "--max-fraction 0.01", "--max-diff 300", "--max-flip nan", "--max-flip 2", "--ppd 0",
          "--flip-map x.jpg"}) {
        EXPECT_EQ(compare(options), 2) << options << "\n" << output;
        EXPECT_NE(output.find("error: --"), std::string::npos) << options << "\n" << output;
    }
}

} // namespace
