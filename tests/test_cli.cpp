// The `render` program as a user runs it: every scene renders, bad input gets a clear error and
// a non-zero exit, and no output file is left half-written.
#include "image_io.h"
#include "support.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace {

using Result = ssgi::test::CommandResult;

Result run(const std::string& arguments, const std::string& environment = "") {
    return ssgi::test::runCommand(environment + " " + SSGI_RENDER_BINARY + " " + arguments);
}

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() /
              ("ssgi-cli-" + std::to_string(getpid()) + "-" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string file(const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
        return (dir / name).string();
    }
    // Nothing but finished files: no temporaries left behind.
    void expectNoTemporaries() {
        for (const auto& entry : fs::directory_iterator(dir))
            EXPECT_EQ(entry.path().filename().string().rfind(".tmp", 0), std::string::npos)
                << entry.path();
    }
    fs::path dir;
};

// Every scene in scenes/ renders through `render` with the validation layer on, to an image
// that is not black.
TEST_F(Cli, EverySceneRenders) {
    size_t scenes = 0;
    for (const auto& entry : fs::directory_iterator(ssgi::test::sourcePath("scenes"))) {
        if (entry.path().extension() != ".json") continue;
        ++scenes;
        const std::string png = (dir / (entry.path().stem().string() + ".png")).string();
        Result r = run(entry.path().string() + " --size 96x72 --validation --output " + png);
        ASSERT_EQ(r.status, 0) << entry.path() << "\n" << r.output;
        uint32_t w, h;
        std::vector<float> pixels = ssgi::readImage(png, w, h);
        EXPECT_EQ(w, 96u);
        EXPECT_EQ(h, 72u);
        double sum = 0.0;
        for (size_t i = 0; i < pixels.size(); i += 4)
            sum += pixels[i] + pixels[i + 1] + pixels[i + 2];
        EXPECT_GT(sum / (w * h * 3), 0.02) << entry.path() << " rendered (nearly) black";
        EXPECT_TRUE(fs::exists(fs::path(png).replace_extension(".exr")));
    }
    EXPECT_GE(scenes, 9u) << "the default scene and the eight model scenes";
    expectNoTemporaries();
}

// Every model of scenes/models/ given bare (no scene file) comes out framed and lit: its
// default camera, light, sky and ground give a mean brightness of at least 40/255 (before
// they did, all eight stayed below 13/255).
TEST_F(Cli, BareModelsComeOutLit) {
    size_t models = 0;
    for (const auto& entry : fs::directory_iterator(ssgi::test::sourcePath("scenes/models"))) {
        if (entry.path().extension() != ".glb") continue;
        ++models;
        const std::string png = (dir / (entry.path().stem().string() + ".png")).string();
        Result r = run(entry.path().string() + " --size 64x64 --validation --output " + png);
        ASSERT_EQ(r.status, 0) << entry.path() << "\n" << r.output;
        uint32_t w, h;
        const std::vector<float> pixels = ssgi::readImage(png, w, h);
        double sum = 0.0;
        for (size_t i = 0; i < pixels.size(); i += 4)
            sum += pixels[i] + pixels[i + 1] + pixels[i + 2];
        EXPECT_GE(255.0 * sum / (w * h * 3), 40.0) << entry.path() << " came out too dark";
    }
    EXPECT_GE(models, 8u);
}

TEST_F(Cli, ProfilePrintsEveryPassAndWritesJson) {
    const std::string json = (dir / "profile.json").string();
    Result r = run("--size 64x64 --frames 3 --profile --profile-json " + json + " --output " +
                   (dir / "out.png").string());
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char* pass :
         {"gbuffer", "rsm", "shadow", "direct", "ao", "indirect", "upsample", "shadow.temporal",
          "ao.temporal", "indirect.temporal", "composite", "total", "device:"})
        EXPECT_NE(r.output.find(pass), std::string::npos) << pass << " missing in\n" << r.output;
    std::ifstream in(json);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_NE(text.find("\"median_ms\""), std::string::npos);
    EXPECT_NE(text.find("\"driver\""), std::string::npos);
}

struct BadInput {
    std::string arguments, environment, expected;
};

TEST_F(Cli, BadInputGetsAClearErrorAndNoOutput) {
    const std::string out = " --output " + (dir / "bad.png").string();
    const std::string malformed = file("malformed.json", "{ \"camera\": { \"position\": [0, 1, ");
    const std::string unknownKey = file("unknown.json", "{ \"camra\": {} }");
    const std::string truncated = file("truncated.glb", "glTF\x02\0\0\0");
    const BadInput cases[] = {
        {"/no/such/scene.json" + out, "", "/no/such/scene.json"},
        {malformed + out, "", "malformed.json"},
        {unknownKey + out, "", "camra"},
        {truncated + out, "", "truncated.glb"},
        {"--size 0x64" + out, "", "size"},
        {"--size 20000x20000" + out, "", "largest 2D image"},
        {"--size banana" + out, "", "--size"},
        {"--frames 0" + out, "", "--frames"},
        {"--view nonsense" + out, "", "unknown view"},
        {"--no-such-option" + out, "", "unknown option"},
        {"--output " + (dir / "x.jpg").string(), "", ".png"},
        {"--device no-such-gpu" + out, "", "no usable Vulkan device named 'no-such-gpu'"},
        {"" + out, "VK_ICD_FILENAMES=/nonexistent.json VK_DRIVER_FILES=/nonexistent.json",
         "Vulkan"},
    };
    for (const BadInput& c : cases) {
        Result r = run(c.arguments, c.environment);
        EXPECT_NE(r.status, 0) << c.arguments;
        EXPECT_NE(r.output.find("error: "), std::string::npos) << c.arguments << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos)
            << "'" << c.expected << "' not named for: " << c.arguments << "\n"
            << r.output;
        EXPECT_FALSE(fs::exists(dir / "bad.png")) << c.arguments;
    }
    expectNoTemporaries();
}

} // namespace
