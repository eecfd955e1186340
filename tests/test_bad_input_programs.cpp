// The programs as a user runs them: exit statuses, no partial output, images that stay finite
// however bright the scene, a PNG and its EXR landing together.
#include "app/cli.h"
#include "bad_input.h"
#include "image_io.h"
#include "renderer.h"
#include "support.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <regex>
#include <sstream>
#include <sys/stat.h>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace ssgi;
using ssgi::test::BadInput;

namespace {

// The programs as a user runs them (beside this test's build folder; CMake builds them first):
// the exit status says bad input (2) or device (1), and nothing is left half-written.
TEST_F(BadInput, ProgramsExitStatusAndNoPartialOutput) {
    const fs::path build = fs::read_symlink("/proc/self/exe").parent_path().parent_path();
    const std::string render = (build / "render").string(), walk = (build / "walkthrough").string();
    ASSERT_TRUE(fs::exists(render) && fs::exists(walk)) << "render and walkthrough are built first";
    const std::string box = test::sourcePath("tests/scenes/empty-box.json") + " --size 16x16";
    const std::string out = " --output " + (dir_ / "out.png").string();
    const std::string blocked = write("blocker", "a file where a folder is wanted") + "/x";
    const std::string noDevice = "VK_ICD_FILENAMES=/nonexistent.json VK_DRIVER_FILES=/none.json";
    const std::string timings = (dir_ / "t.csv").string();
    const std::string manifest = write("icd.json", R"({"ICD": {"library_path": )");
    struct Case {
        std::string command;
        int status;
        std::string expected;
    };
    const Case cases[] = {
        {render + " --set ssdo_samples=0" + out, 2, "'ssdo_samples' is 0"},
        {render + " --set indirect_vpls=100000000" + out, 2, "indirect_vpls"},
        {render + " --set shadow_taps=nan" + out, 2, "'shadow_taps' is nan"},
        {render + " --set exposure=inf" + out, 2, "'exposure' is inf"},
        {render + " --set cache_rotations=1e300" + out, 2, "cache_rotations"},
        {render + " --set ao_directions=2.5" + out, 2, "must be a whole number"},
        {render + " --size 64x0" + out, 2, "64x0"},
        {render + " " + box + " --output " + blocked + ".png", 2, "blocker/x.png"},
        {render + " " + box + out + " --profile-json " + blocked + ".json", 2, "blocker/x.json"},
        {noDevice + " " + render + " " + box + out, 1, "Vulkan"},
        // The loader calls a malformed manifest running out of memory; the message names it.
        {"VK_DRIVER_FILES=" + manifest + " " + render + " " + box + out, 1,
         "manifest " + manifest + ": not valid JSON"},
        {walk + " " + box, 2, "camera_path"},
        {walk + " " + box + " --still --timings t.txt", 2, "--timings"},
        {walk + " " + box + " --still --frames 2 --timings " + timings + " --frames-dir " + blocked,
         2, "blocker/x"},
        {noDevice + " " + walk + " " + box + " --still --timings " + timings, 1, "Vulkan"},
    };
    for (const Case& c : cases) {
        const test::CommandResult run = test::runCommand(c.command);
        const std::string& output = run.output;
        EXPECT_EQ(run.status, c.status) << c.command << output;
        EXPECT_NE(output.find("error: "), std::string::npos) << c.command << "\n" << output;
        EXPECT_NE(output.find(c.expected), std::string::npos) << c.command << "\n" << output;
        EXPECT_FALSE(fs::exists(timings)) << c.command;
        EXPECT_FALSE(fs::exists(dir_ / "out.json")) << c.command;
        // The one finished file a failing run may leave is the PNG it wrote before failing.
        for (const auto& entry : fs::directory_iterator(dir_))
            EXPECT_EQ(entry.path().filename().string().rfind(".tmp", 0), std::string::npos)
                << entry.path();
    }
}

// Values inside the scene file's ranges that overflow a half float (65504): a sky of 1e6 and a
// light of 1e12 × 1e6 wrote an EXR of +Inf with exit status 0, from render and from reference.
// Now the lights are scaled to fit the intermediate images, the EXR takes 32-bit floats where a
// value needs them, and no image holding a NaN or Inf is ever written.
TEST_F(BadInput, BrightScenesGiveFiniteImages) {
    const fs::path build = fs::read_symlink("/proc/self/exe").parent_path().parent_path();
    std::ifstream in(test::sourcePath("tests/scenes/empty-box.json"));
    json scene = json::parse(in);
    scene["sky"] = {{"color", {1e6, 1e6, 1e6}}};
    const std::string sky = write("sky.json", scene.dump());
    scene.erase("sky");
    scene["light"]["intensity"] = 1e12;
    scene["light"]["color"] = {1e6, 1e6, 1e6};
    const std::string light = write("light.json", scene.dump());
    for (const std::string& file : {sky, light}) {
        const std::string stem = fs::path(file).stem().string();
        const std::string png = (dir_ / (stem + ".png")).string();
        const std::string refExr = (dir_ / (stem + "-ref.exr")).string();
        const test::CommandResult render = test::runCommand((build / "render").string() + " " +
                                                            file + " --size 16x16 --output " + png);
        const test::CommandResult reference =
            test::runCommand((build / "reference").string() + " " + file +
                             " --size 8x8 --spp 2 --no-cache --quiet --output " + refExr);
        for (const auto& [run, exr] :
             {std::pair{render, dir_ / (stem + ".exr")}, std::pair{reference, fs::path(refExr)}}) {
            SCOPED_TRACE(exr.string());
            ASSERT_EQ(run.status, 0) << run.output;
            uint32_t w = 0, h = 0;
            const std::vector<float> pixels = readImage(exr.string(), w, h);
            float largest = 0.0f;
            for (float v : pixels) {
                ASSERT_TRUE(std::isfinite(v));
                largest = std::max(largest, v);
            }
            EXPECT_GT(largest, 65504.0f); // brighter than half floats hold, and kept as it is
        }
    }
    // Scaled, not clipped: a sky of 1e6 is drawn as a sky of 1e6 / 1024 (which needs no scale),
    // times 1024. (The image is not linear in the sky's brightness: compare like with like.) No
    // spot light, which would not scale with the sky (the sky visibility darkens some pixels'
    // sky enough for a default light to show).
    scene["light"]["intensity"] = 0;
    scene["light"]["color"] = {1, 1, 1};
    scene["sky"] = {{"color", {1e6 / 1024, 1e6 / 1024, 1e6 / 1024}}};
    const std::string unitSky = write("unit-sky.json", scene.dump());
    ASSERT_EQ(test::runCommand((build / "render").string() + " " + unitSky +
                               " --size 16x16 --output " + (dir_ / "unit-sky.png").string())
                  .status,
              0);
    scene["sky"] = {{"color", {1e6, 1e6, 1e6}}};
    const std::string brightSky = write("bright-sky.json", scene.dump());
    ASSERT_EQ(test::runCommand((build / "render").string() + " " + brightSky +
                               " --size 16x16 --output " + (dir_ / "bright-sky.png").string())
                  .status,
              0);
    uint32_t w = 0, h = 0;
    const std::vector<float> unit = readImage((dir_ / "unit-sky.exr").string(), w, h);
    const std::vector<float> bright = readImage((dir_ / "bright-sky.exr").string(), w, h);
    ASSERT_EQ(unit.size(), bright.size());
    for (size_t i = 0; i < unit.size(); ++i)
        if (i % 4 != 3) { // alpha is 1
            ASSERT_NEAR(bright[i], unit[i] * 1024.0f, 2e-3f * unit[i] * 1024.0f) << i;
        }
    // The final guard: a NaN or Inf is a renderer's failure (exit status 1), and nothing lands.
    const std::vector<float> bad = {0.5f, NAN, 0.5f, 1.0f};
    for (const char* name : {"nan.exr", "nan.png"}) {
        try {
            writeImage((dir_ / name).string(), 1, 1, bad);
            ADD_FAILURE() << name << " was written";
        } catch (const InputError&) {
            ADD_FAILURE() << "a non-finite image is not bad input";
        } catch (const std::runtime_error& error) {
            EXPECT_NE(std::string(error.what()).find("NaN or infinite"), std::string::npos);
        }
        EXPECT_FALSE(fs::exists(dir_ / name));
    }
}

// The PNG and the EXR beside it land together or not at all: when the EXR's name is taken by a
// folder the PNG was left behind, and the message ended in "Success" (a stale errno).
TEST_F(BadInput, PngAndExrLandTogetherOrNotAtAll) {
    const fs::path build = fs::read_symlink("/proc/self/exe").parent_path().parent_path();
    const std::string render = (build / "render").string() + " " +
                               test::sourcePath("tests/scenes/empty-box.json") + " --size 16x16";
    fs::create_directories(dir_ / "new.exr");
    fs::create_directories(dir_ / "old.exr");
    write("old.png", "what was there before");
    for (const char* stem : {"new", "old"}) {
        SCOPED_TRACE(stem);
        const test::CommandResult run =
            test::runCommand(render + " --output " + (dir_ / stem).string() + ".png");
        EXPECT_EQ(run.status, 2) << run.output;
        EXPECT_NE(run.output.find(std::string(stem) + ".exr: cannot move the finished file into "
                                                      "place: Is a directory"),
                  std::string::npos)
            << run.output;
        EXPECT_EQ(run.output.find("Success"), std::string::npos) << run.output;
    }
    EXPECT_FALSE(fs::exists(dir_ / "new.png"));
    std::ifstream old(dir_ / "old.png");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(old), {}), "what was there before");
    for (const auto& entry : fs::directory_iterator(dir_)) // no temporary, no backup left
        EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
}

// Every program's arguments are checked as render's are, and what reaches the user is an
// `error:` line saying what failed: never a raw std::bad_alloc or std::filesystem message.
TEST_F(BadInput, EveryProgramChecksItsArgumentsAndSaysWhatFailed) {
    const fs::path build = fs::read_symlink("/proc/self/exe").parent_path().parent_path();
    const std::string box = test::sourcePath("tests/scenes/empty-box.json");
    // A loop of symbolic links is one, not a missing file.
    fs::create_symlink("loop-b.json", dir_ / "loop-a.json");
    fs::create_symlink("loop-a.json", dir_ / "loop-b.json");
    struct Case {
        std::string program, arguments, expected;
    };
    const Case cases[] = {
        {"render", box + " --size 0x16", "image size 0x16 is outside 1.."},
        {"stability", "--quick --size 0x16", "--size: at least 16x16"},
        {"walkthrough", box + " --still --size 16x0", "image size 16x0 is outside 1.."},
        {"viewer", "--effect bogus", "--effect: unknown effect 'bogus'"},
        {"render", (dir_ / "loop-a.json").string() + " --size 16x16",
         "loop-a.json: a loop of symbolic links"},
        // One range, whatever the value (0 was "must be at least 1", -1 "in 0..1000000").
        {"render", box + " --frames 0", "--frames: '0' is not a whole number in 1..1000000"},
        {"render", box + " --frames -1", "--frames: '-1' is not a whole number in 1..1000000"},
        {"walkthrough", box + " --still --frames 0",
         "--frames: '0' is not a whole number in 1..1000000"},
        // An unknown command is an error, not the usage alone.
        {"benchmark", "--bogus",
         "error: unknown command '--bogus': the first argument is sweep, walkthrough, indirect or "
         "cache-fixes"},
        {"benchmark", "", "error: no command given"},
    };
    for (const Case& c : cases) {
        const fs::path program = build / c.program;
        if (!fs::exists(program)) continue; // the viewer and stability are optional builds
        SCOPED_TRACE(c.program + " " + c.arguments);
        const test::CommandResult run = test::runCommand(program.string() + " " + c.arguments);
        EXPECT_EQ(run.status, 2) << run.output;
        EXPECT_NE(run.output.find("error: "), std::string::npos) << run.output;
        EXPECT_NE(run.output.find(c.expected), std::string::npos) << run.output;
    }

    // What guardedMain makes of the exceptions that carry no words for a user.
    const auto said = [](int (*run)(int, char**)) {
        testing::internal::CaptureStderr();
        const int status = cli::guardedMain(0, nullptr, run);
        return std::pair{status, testing::internal::GetCapturedStderr()};
    };
    auto [status, text] = said([](int, char**) -> int { throw std::bad_alloc(); });
    EXPECT_EQ(status, 2);
    EXPECT_EQ(text.rfind("error: out of memory: ", 0), 0u) << text;
    std::tie(status, text) = said([](int, char**) -> int {
        fs::file_size("/nonexistent/ssgi-test");
        return 0;
    });
    EXPECT_EQ(status, 2);
    EXPECT_EQ(text, "error: /nonexistent/ssgi-test: No such file or directory\n");
}

} // namespace
