// The two programs of the ground truth, `compare` and `reference`, as a user runs them: their
// tables, JSON and maps, the reference's noise in compare's figures, every scene referenced, the
// reference's cache, and bad input named (the metrics themselves: test_metrics.cpp).
#include "image_io.h"
#include "metrics/comparison.h"
#include "support.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace ssgi;
using namespace ssgi::metrics;
using test::sourcePath;

namespace {

Image constant(uint32_t w, uint32_t h, float value) {
    return {w, h, std::vector<float>(size_t(w) * h * 4, value)};
}

// The programs as a user runs them; they sit beside the tests' folder in the build tree.
class Program : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("ssgi-programs-" + std::to_string(getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    // Runs `program` (compare or reference) with `arguments`; stdout and stderr in `output`.
    int run(const std::string& program, const std::string& arguments, std::string& output) {
        const test::CommandResult r = test::runCommand(binary(program) + " " + arguments);
        output = r.output;
        return r.status;
    }
    static std::string binary(const std::string& program) {
        const fs::path path =
            fs::read_symlink("/proc/self/exe").parent_path().parent_path() / program;
        if (!fs::exists(path)) ADD_FAILURE() << path << " is not built";
        return path.string();
    }
    std::string image(const std::string& name, const Image& image) {
        writeImage((dir / name).string(), image.width, image.height, image.rgba);
        return (dir / name).string();
    }
    fs::path dir;
};

TEST_F(Program, CompareWritesTableJsonAndErrorMap) {
    const std::string a = image("a.exr", constant(32, 24, 0.75f));
    const std::string b = image("b.exr", constant(32, 24, 0.5f));
    Image maskImage = constant(32, 24, 0.0f);
    for (size_t i = 0; i < maskImage.pixels(); ++i) {
        maskImage.rgba[4 * i] = i < 32 ? 1.0f : 0.0f; // the top row
        maskImage.rgba[4 * i + 3] = 1.0f;             // opaque: PNG readers premultiply
    }
    const std::string mask = image("mask.png", maskImage);
    const std::string json = (dir / "out.json").string(), map = (dir / "map.png").string();
    std::string output;
    ASSERT_EQ(run("compare",
                  a + " " + b + " --edge-band 2 --mask " + mask + " --json " + json +
                      " --error-map " + map,
                  output),
              0)
        << output;
    EXPECT_NE(output.find("relMSE"), std::string::npos) << output;
    nlohmann::json j;
    std::ifstream(json) >> j;
    ASSERT_EQ(j["regions"].size(), 3u);
    EXPECT_EQ(j["regions"][0]["pixels"], 32 * 24);
    EXPECT_NEAR(j["regions"][0]["rmse"].get<double>(), 0.25, 1e-3); // half floats in the EXR
    EXPECT_EQ(j["regions"][1]["pixels"], 32 * 24 - 28 * 20);
    EXPECT_EQ(j["regions"][2]["pixels"], 32);
    uint32_t w = 0, h = 0;
    readImage(map, w, h);
    EXPECT_EQ(w, 32u);
    EXPECT_EQ(h, 24u);
}

TEST_F(Program, CompareNamesBadInput) {
    const std::string a = image("a.exr", constant(32, 24, 0.5f));
    const std::string small = image("small.exr", constant(16, 24, 0.5f));
    std::string output;
    EXPECT_EQ(run("compare", a + " " + (dir / "missing.exr").string(), output), 2);
    EXPECT_NE(output.find("error: " + (dir / "missing.exr").string()), std::string::npos) << output;
    EXPECT_EQ(run("compare", a + " " + small, output), 2);
    EXPECT_NE(output.find(small + ": 16x24 differs"), std::string::npos) << output;
    EXPECT_EQ(run("compare", a + " " + a + " --mask " + small, output), 2);
    EXPECT_NE(output.find(small), std::string::npos) << output;
    EXPECT_EQ(run("compare", a + " " + a + " --edge-band 0", output), 2);
    EXPECT_NE(output.find("--edge-band"), std::string::npos) << output;
    EXPECT_EQ(run("compare", a, output), 2);
    EXPECT_EQ(run("compare", a + " " + a + " --error-map " + (dir / "map.jpg").string(), output),
              2);
    EXPECT_FALSE(fs::exists(dir / "map.jpg"));
    // Images that cannot be compared: a tonemapped PNG against a linear EXR, and a
    // reference holding NaN (written past writeImage, which refuses to write one).
    const std::string png = image("a.png", constant(32, 24, 0.5f));
    EXPECT_EQ(run("compare", png + " " + a, output), 2);
    EXPECT_NE(output.find("hold different quantities"), std::string::npos) << output;
    const std::string nan = (dir / "nan.exr").string();
    {
        std::vector<float> pixels = constant(32, 24, 0.5f).rgba;
        pixels[4 * 7] = std::numeric_limits<float>::quiet_NaN();
        auto out = OIIO::ImageOutput::create(nan);
        ASSERT_TRUE(out);
        ASSERT_TRUE(out->open(nan, OIIO::ImageSpec(32, 24, 4, OIIO::TypeDesc::FLOAT)));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        out->close();
    }
    EXPECT_EQ(run("compare", a + " " + nan, output), 2);
    EXPECT_NE(output.find("1 pixels are NaN or infinite"), std::string::npos) << output;
}

// An EXR's channels are read by name: R, G, B and A wherever they stand (a depth Z beside them
// is left alone), Y alone as grey; X, Y, Z, a pair R, G, or layers such as normal.X are refused
// naming what the file holds, never compared as RGB by position.
TEST_F(Program, CompareReadsChannelsByName) {
    const auto exr = [&](const std::string& name, const std::vector<std::string>& channels) {
        const std::string path = (dir / name).string();
        OIIO::ImageSpec spec(4, 3, int(channels.size()), OIIO::TypeDesc::FLOAT);
        spec.channelnames = channels;
        std::vector<float> values(12 * channels.size());
        for (size_t i = 0; i < values.size(); ++i)
            values[i] = 0.1f * float(i % channels.size() + 1); // channel k holds 0.1 (k + 1)
        auto out = OIIO::ImageOutput::create(path);
        EXPECT_TRUE(out && out->open(path, spec) &&
                    out->write_image(OIIO::TypeDesc::FLOAT, values.data()) && out->close());
        return path;
    };
    uint32_t w = 0, h = 0;
    // Written Z, B, R, A, G: R is the file's third channel, G its fifth.
    const std::vector<float> rgba = readImage(exr("zbrag.exr", {"Z", "B", "R", "A", "G"}), w, h);
    ASSERT_EQ(rgba.size(), 4u * 12u);
    EXPECT_FLOAT_EQ(rgba[0], 0.3f);
    EXPECT_FLOAT_EQ(rgba[1], 0.5f);
    EXPECT_FLOAT_EQ(rgba[2], 0.2f);
    EXPECT_FLOAT_EQ(rgba[3], 0.4f);
    const std::vector<float> grey = readImage(exr("ya.exr", {"Y", "A"}), w, h);
    EXPECT_EQ(std::vector<float>(grey.begin(), grey.begin() + 4),
              (std::vector<float>{0.1f, 0.1f, 0.1f, 0.2f}));
    const std::pair<std::vector<std::string>, std::string> refused[] = {
        {{"X", "Y", "Z"}, "X, Y, Z"},
        {{"R", "G"}, "R, G"},
        {{"Y", "Z"}, "Y, Z"},
        {{"normal.X", "normal.Y", "normal.Z", "depth.Z"}, "depth.Z, normal.X, normal.Y, normal.Z"}};
    for (const auto& [channels, named] : refused) {
        const std::string path = exr("refused.exr", channels);
        std::string output;
        EXPECT_EQ(run("compare", path + " " + path, output), 2) << named << "\n" << output;
        EXPECT_NE(output.find("error: " + path + ": holds the channels " + named + ";"),
                  std::string::npos)
            << output;
    }
}

// A reference's EXR records its samples and estimated noise in its header; compare prints the
// relMSE that noise accounts for beside each figure, warns when a figure is within 10x of it (two
// seeds of one reference differ by their noise alone), and says when a reference records none.
TEST_F(Program, ComparePrintsTheReferencesOwnNoise) {
    const std::string common = sourcePath("scenes/cornell-box.json") +
                               " --mode ao --size 24x24 --noise 0.05 --quiet --no-cache";
    const std::string one = (dir / "one.exr").string(), two = (dir / "two.exr").string();
    std::string output;
    ASSERT_EQ(run("reference", common + " --seed 1 --output " + one, output), 0) << output;
    ASSERT_EQ(run("reference", common + " --seed 2 --output " + two, output), 0) << output;
    ImageAttributes header;
    uint32_t w = 0, h = 0;
    readImage(two, w, h, &header);
    ASSERT_EQ(header.ints.count("ssgi:samples"), 1u);
    ASSERT_EQ(header.floats.count("ssgi:noise"), 1u);
    const int samples = header.ints["ssgi:samples"];
    const float noise = header.floats["ssgi:noise"];
    EXPECT_GE(samples, 16);
    EXPECT_GT(noise, 0.0f);
    EXPECT_LE(noise, 0.05f);
    EXPECT_EQ(header.texts["ssgi:mode"], "ao");
    EXPECT_NE(output.find(std::to_string(samples) + " spp"), std::string::npos) << output;

    const std::string json = (dir / "two.json").string();
    EXPECT_EQ(run("compare", one + " " + two + " --json " + json, output), 0);
    char line[128];
    std::snprintf(line, sizeof line, "%s: a reference of %d spp, noise %.2f%%", two.c_str(),
                  samples, 100.0 * noise);
    EXPECT_NE(output.find(line), std::string::npos) << output;
    EXPECT_NE(output.find("warning: image: relMSE"), std::string::npos) << output;
    EXPECT_NE(output.find("within 10x of the references' own noise"), std::string::npos) << output;
    nlohmann::json j;
    std::ifstream(json) >> j;
    EXPECT_EQ(j["reference_noise"]["samples"], samples);
    EXPECT_NEAR(j["reference_noise"]["noise"].get<double>(), noise, 1e-6);
    // Noise floor: both references' noise^2; two seeds differ by about that much.
    const double floor = j["regions"][0]["relmse_noise"].get<double>();
    const double relMse = j["regions"][0]["relmse"].get<double>();
    std::printf("two seeds: relMSE %.3g, the references' noise^2 summed %.3g\n", relMse, floor);
    EXPECT_TRUE(j["regions"][0]["within_noise_margin"].get<bool>());
    EXPECT_GT(relMse, 0.3 * floor);
    EXPECT_LT(relMse, 3.0 * floor);

    // A reference that records nothing: said so, and nothing to warn about.
    const std::string plain = image("plain.exr", loadImage(two));
    EXPECT_EQ(run("compare", one + " " + plain, output), 0);
    EXPECT_NE(output.find(plain + " records no noise of its own"), std::string::npos) << output;
    EXPECT_EQ(output.find("warning: image"), std::string::npos) << output;
}

// Every scene in scenes/ renders, to an image that is neither black nor NaN.
TEST_F(Program, ReferenceRendersEveryScene) {
    size_t scenes = 0;
    for (const auto& entry : fs::directory_iterator(sourcePath("scenes"))) {
        if (entry.path().extension() != ".json") continue;
        ++scenes;
        const std::string exr = (dir / (entry.path().stem().string() + ".exr")).string();
        std::string output;
        ASSERT_EQ(
            run("reference",
                entry.path().string() + " --size 32x24 --spp 2 --quiet --no-cache --output " + exr,
                output),
            0)
            << entry.path() << "\n"
            << output;
        uint32_t w = 0, h = 0;
        const std::vector<float> pixels = readImage(exr, w, h);
        ASSERT_EQ(w * h, 32u * 24u);
        double sum = 0.0;
        for (size_t i = 0; i < pixels.size(); i += 4)
            sum += pixels[i] + pixels[i + 1] + pixels[i + 2];
        EXPECT_TRUE(std::isfinite(sum)) << entry.path();
        EXPECT_GT(sum, 0.0) << entry.path() << " rendered black";
    }
    EXPECT_GE(scenes, 9u);
}

TEST_F(Program, ReferenceSecondRunComesFromTheCache) {
    const std::string common = sourcePath("scenes/cornell-box.json") +
                               " --mode ao --size 24x24 --spp 4 --quiet --cache " +
                               (dir / "cache").string() + " --output ";
    std::string output;
    ASSERT_EQ(run("reference",
                  common + (dir / "a.exr").string() + " --png " + (dir / "a.png").string(), output),
              0)
        << output;
    EXPECT_NE(output.find("rendered"), std::string::npos) << output;
    ASSERT_EQ(run("reference", common + (dir / "b.exr").string(), output), 0) << output;
    EXPECT_NE(output.find("from the cache"), std::string::npos) << output;
    uint32_t w, h;
    EXPECT_EQ(readImage((dir / "a.exr").string(), w, h), readImage((dir / "b.exr").string(), w, h));
    EXPECT_TRUE(fs::exists(dir / "a.png"));
}

TEST_F(Program, ReferenceNamesBadInput) {
    const std::string scene = sourcePath("scenes/cornell-box.json");
    const std::string out =
        " --quiet --no-cache --size 8x8 --spp 1 --output " + (dir / "x.exr").string();
    struct Case {
        std::string arguments, message;
    };
    const Case cases[] = {
        {(dir / "missing.json").string() + out, (dir / "missing.json").string()},
        {scene + out + " --mode glossy", "--mode: 'glossy'"},
        {scene + out + " --mode direct --jitter", "--jitter"},
        {scene + out + " --spp 0", "--spp"},
        {scene + out + " --size 0x8", "--size"},
        {scene + out + " --noise 2", "--noise"},
        {scene + out + " --noise 1e-9", "--noise"},
        {sourcePath("tests/scenes/empty-box.json") + out + " --time 1", "camera_path"},
        {scene + out + " --frobnicate", "--frobnicate"},
        {scene + " --quiet --output " + (dir / "x.png").string(), "--output"},
    };
    for (const Case& c : cases) {
        std::string output;
        EXPECT_EQ(run("reference", c.arguments, output), 2) << c.arguments << "\n" << output;
        EXPECT_NE(output.find("error: "), std::string::npos) << output;
        EXPECT_NE(output.find(c.message), std::string::npos) << c.arguments << "\n" << output;
    }
    EXPECT_FALSE(fs::exists(dir / "x.exr"));
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// A size whose sums do not fit in memory is refused before anything is allocated, naming the size
// and the memory, not met with std::bad_alloc (or the process killed) after seconds of allocating.
// The address space is limited to 4 GB here so that the answer is the same on any machine.
TEST_F(Program, ReferenceRefusesASizeBeyondMemory) {
    const test::CommandResult r = test::runCommand(
        "ulimit -v 4000000 && " + binary("reference") + " " +
        sourcePath("scenes/cornell-box.json") + " --quiet --no-cache --size 16384x16384 --output " +
        (dir / "huge.exr").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("error: --size 16384x16384: the reference needs 19.3 GB of memory"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("bad_alloc"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "huge.exr"));
}

} // namespace
