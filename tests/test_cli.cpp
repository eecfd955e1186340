// The `render` program as a user runs it: every scene renders, a shipped scene is found by its
// name from any folder, bad input gets a clear error and a non-zero exit, and no output file is
// left half-written.
#include "app/cli.h"
#include "image_io.h"
#include "support.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sys/stat.h>

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
    // The screen-space bounce: its filter's pass is among those looked for below.
    Result r = run("--size 64x64 --frames 3 --set indirect_method=1 --profile --profile-json " +
                   json + " --output " + (dir / "out.png").string());
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char* pass : {"gbuffer", "rsm", "shadow", "direct", "ao", "indirect",
                             "indirect.filter_x", "temporal", "composite", "sum of passes",
                             "host clock", "device:", "2 timed frames after 1 warm-up frame"})
        EXPECT_NE(r.output.find(pass), std::string::npos) << pass << " missing in\n" << r.output;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(j["warmup_frames"], 1);
    EXPECT_EQ(j["host_frames_ms"].size(), 2u);
    for (const auto& pass : j["passes"]) {
        EXPECT_EQ(pass["frames_ms"].size(), 2u);
        EXPECT_LE(pass["min_ms"].get<double>(), pass["median_ms"].get<double>());
        EXPECT_LE(pass["median_ms"].get<double>(), pass["max_ms"].get<double>());
    }
    EXPECT_TRUE(j.contains("driver"));
}

// A world cache's table too small for the view leaves pixels without a bounce, and render says
// so without --profile; a table the image sized says nothing.
TEST_F(Cli, AWorldCacheTableTooSmallIsSaid) {
    Result small = run("--size 64x64 --set indirect_method=3 --set world_table_bits=8 --output " +
                       (dir / "small.png").string());
    ASSERT_EQ(small.status, 0) << small.output;
    EXPECT_NE(small.output.find("warning: the world cache's table (256 entries) had no free entry"),
              std::string::npos)
        << small.output;
    Result sized =
        run("--size 64x64 --set indirect_method=3 --output " + (dir / "sized.png").string());
    ASSERT_EQ(sized.status, 0) << sized.output;
    EXPECT_EQ(sized.output.find("world cache's table"), std::string::npos) << sized.output;
}

// The trace opens in ui.perfetto.dev / chrome://tracing: Chrome's trace event format, one
// complete ("X") event per pass that ran and per frame on the host, GPU events of a frame in
// the order the frame declares its passes and not overlapping.
TEST_F(Cli, ProfileTraceHoldsEveryPassInOrderWithoutOverlap) {
    const std::string trace = (dir / "trace.json").string();
    const std::string json = (dir / "profile.json").string();
    Result r = run("--size 64x64 --frames 2 --profile-trace " + trace + " --profile-json " + json +
                   " --output " + (dir / "out.png").string());
    ASSERT_EQ(r.status, 0) << r.output;
    const nlohmann::json t = nlohmann::json::parse(std::ifstream(trace));
    const nlohmann::json profile = nlohmann::json::parse(std::ifstream(json));
    ASSERT_TRUE(t["traceEvents"].is_array());
    std::vector<std::string> declared;
    for (const auto& pass : profile["passes"])
        declared.push_back(pass["name"]);
    std::map<int, std::vector<nlohmann::json>> gpu; // per frame
    int hostFrames = 0;
    for (const auto& e : t["traceEvents"]) {
        ASSERT_TRUE(e.contains("ph") && e.contains("pid") && e.contains("name")) << e.dump();
        if (e["ph"] != "X") continue;
        ASSERT_TRUE(e["ts"].is_number() && e["dur"].is_number()) << e.dump();
        EXPECT_GE(e["dur"].get<double>(), 0.0);
        if (e["cat"] == "host") ++hostFrames;
        if (e["cat"] == "gpu") gpu[e["args"]["frame"].get<int>()].push_back(e);
    }
    EXPECT_EQ(hostFrames, 2);
    ASSERT_EQ(gpu.size(), 2u);
    for (const auto& [frame, events] : gpu) {
        SCOPED_TRACE("frame " + std::to_string(frame));
        // Every event names a declared pass, each at most once, in declared order.
        size_t next = 0;
        for (size_t i = 0; i < events.size(); ++i) {
            const std::string name = events[i]["name"];
            while (next < declared.size() && declared[next] != name)
                ++next;
            ASSERT_LT(next, declared.size()) << name << " out of order or undeclared";
            ++next;
            if (i > 0) {
                EXPECT_LE(events[i - 1]["ts"].get<double>() + events[i - 1]["dur"].get<double>(),
                          events[i]["ts"].get<double>() + 1e-3)
                    << events[i - 1]["name"] << " overlaps " << name;
            }
        }
        // The passes that always run are all there.
        for (const char* pass : {"gbuffer", "shadow", "direct", "ao", "composite"})
            EXPECT_TRUE(std::any_of(events.begin(), events.end(), [&](const nlohmann::json& e) {
                return e["name"] == pass;
            })) << pass;
    }
}

TEST_F(Cli, WalkthroughWritesATraceAndTheHostClockBesideThePasses) {
    const std::string trace = (dir / "walk.json").string();
    const std::string timings = (dir / "timings.json").string();
    Result r = ssgi::test::runCommand(std::string(SSGI_WALKTHROUGH_BINARY) +
                                      " scenes/bunny.json --size 48x48 --frames 3 --timings " +
                                      timings + " --profile-trace " + trace);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("host clock"), std::string::npos) << r.output;
    const nlohmann::json t = nlohmann::json::parse(std::ifstream(trace));
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(timings));
    int hostFrames = 0;
    for (const auto& e : t["traceEvents"])
        hostFrames += e.value("cat", "") == "host";
    EXPECT_EQ(hostFrames, 3);
    ASSERT_EQ(j["host_ms"].size(), 3u);
    for (size_t f = 0; f < 3; ++f)
        EXPECT_GE(j["host_ms"][f].get<double>(), 0.0);
}

// `cmake --install` gives programs that run from anywhere: their shaders are inside them and
// their scenes beside them in PREFIX/share/ssgi.
TEST_F(Cli, InstalledRenderRunsFromAnyDirectory) {
    const fs::path prefix = dir / "prefix";
    Result install = ssgi::test::runCommand("cmake --install " + std::string(SSGI_BUILD_DIR) +
                                            " --prefix " + prefix.string());
    ASSERT_EQ(install.status, 0) << install.output;
    for (const char* program : {"render", "walkthrough", "reference", "compare"})
        EXPECT_TRUE(fs::exists(prefix / "bin" / program)) << program;
    EXPECT_TRUE(fs::exists(prefix / "share/ssgi/scenes/models/bunny.glb"));
    const fs::path png = dir / "installed.png";
    Result r = ssgi::test::runCommand("cd / && " + (prefix / "bin/render").string() +
                                      " --size 48x48 --output " + png.string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find((prefix / "share/ssgi/scenes/cornell-box.json").string()),
              std::string::npos)
        << "the default scene comes from the installed share/ssgi\n"
        << r.output;
    uint32_t w = 0, h = 0;
    const std::vector<float> rgba = ssgi::readImage(png.string(), w, h);
    ASSERT_EQ(w, 48u);
    double sum = 0.0;
    for (size_t i = 0; i < rgba.size(); i += 4)
        sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
    EXPECT_GT(sum / (w * h * 3), 0.02) << "rendered (nearly) black";
    // A scene given by path renders too.
    r = ssgi::test::runCommand("cd / && " + (prefix / "bin/render").string() + " " +
                               (prefix / "share/ssgi/scenes/bunny.json").string() +
                               " --size 32x32 --output " + (dir / "bunny.png").string());
    EXPECT_EQ(r.status, 0) << r.output;
    // And a shipped scene by its name, from the installed share/ssgi.
    r = ssgi::test::runCommand("cd / && " + (prefix / "bin/render").string() +
                               " bunny --size 32x32 --output " +
                               (dir / "bunny-named.png").string());
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find((prefix / "share/ssgi/scenes/bunny.json").string()), std::string::npos)
        << r.output;
}

// A program's SCENE is a path, or a shipped scene's name (cli::resolveScene, the one place the
// programs resolve it): a path that is there wins, a bare name that is no file is the shipped
// scene, and a name that is neither is bad input listing the names.
TEST_F(Cli, ASceneNameResolvesToTheShippedScene) {
    const std::string shipped = std::string(SSGI_SOURCE_DIR) + "/scenes/";
    EXPECT_EQ(ssgi::cli::resolveScene("cornell-box"), shipped + "cornell-box.json");
    EXPECT_EQ(ssgi::cli::resolveScene("sponza"), shipped + "sponza.json");
    const std::vector<std::string> names = ssgi::cli::shippedSceneNames();
    EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
    for (const char* name : {"bunny", "conference", "cornell-box", "sibenik", "sponza"})
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    // Paths are the loader's to find or refuse, whether there or not.
    EXPECT_EQ(ssgi::cli::resolveScene("missing.json"), "missing.json");
    EXPECT_EQ(ssgi::cli::resolveScene("no/such/cornell-box"), "no/such/cornell-box");
    try {
        ssgi::cli::resolveScene("cornell-bx");
        ADD_FAILURE() << "an unknown name was taken";
    } catch (const ssgi::InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("'cornell-bx'"), std::string::npos) << message;
        EXPECT_NE(message.find("bunny, conference, cornell-box"), std::string::npos) << message;
    }
    // A file of that name in the working folder wins over the shipped scene.
    const fs::path before = fs::current_path();
    fs::current_path(dir);
    std::ofstream("cornell-box") << "{}";
    const std::string local = ssgi::cli::resolveScene("cornell-box");
    fs::current_path(before);
    EXPECT_EQ(local, "cornell-box");
}

TEST_F(Cli, ProgramsTakeAShippedSceneByNameFromAnyFolder) {
    const std::string in = "cd " + dir.string() + " && ";
    Result r = ssgi::test::runCommand(in + SSGI_RENDER_BINARY + " cornell-box --size 16x16" +
                                      " --output named.png");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(std::string(SSGI_SOURCE_DIR) + "/scenes/cornell-box.json"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(fs::exists(dir / "named.png"));
    // Every program that takes a scene refuses an unknown name alike: exit 2, the names listed.
    for (const std::string program :
         {std::string(SSGI_RENDER_BINARY), std::string(SSGI_WALKTHROUGH_BINARY),
          std::string(SSGI_BUILD_DIR) + "/reference"}) {
        r = ssgi::test::runCommand(in + program + " cornell-bx --size 16x16");
        EXPECT_EQ(r.status, 2) << program << "\n" << r.output;
        EXPECT_NE(r.output.find("error: 'cornell-bx' is neither a file nor the name of a shipped "
                                "scene; the shipped scenes: bunny, conference, cornell-box"),
                  std::string::npos)
            << program << "\n"
            << r.output;
    }
    // A file there by that name is what is loaded (and, not being a scene file, refused).
    std::ofstream(dir / "cornell-box") << "{}";
    r = ssgi::test::runCommand(in + SSGI_RENDER_BINARY + " cornell-box --size 16x16" +
                               " --output local.png");
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("error: cornell-box: unsupported file type"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir / "local.png"));
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

// Hostile input as a user meets it: a glTF buffer that is a FIFO (it hung), one that is
// a folder, a device reached through `..` (std::bad_alloc, exit 1), an absolute path, a scene
// file saying a key twice (the last won), a size whose images the device cannot hold; each is
// bad input (exit 2) within seconds, naming the file and the problem, and writes nothing.
TEST_F(Cli, HostileInputSecondRound) {
    const std::string out = " --output " + (dir / "bad.png").string();
    ASSERT_EQ(mkfifo((dir / "fifo.bin").c_str(), 0600), 0);
    fs::create_directories(dir / "folder.bin");
    auto gltfWithBuffer = [&](const std::string& name, const std::string& uri) {
        return file(name,
                    R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 36, "uri": ")" +
                        uri + R"("}]})");
    };
    std::string up;
    for (int i = 0; i < 12; ++i)
        up += "../";
    const BadInput cases[] = {
        {gltfWithBuffer("fifo.gltf", "fifo.bin") + out, "",
         "fifo.gltf: external file 'fifo.bin' is a FIFO"},
        {gltfWithBuffer("folder.gltf", "folder.bin") + out, "", "'folder.bin' is a folder"},
        {gltfWithBuffer("zero.gltf", up + "dev/zero") + out, "", "dev/zero' is a character device"},
        {gltfWithBuffer("absolute.gltf", "/etc/passwd") + out, "", "is an absolute path"},
        {file("twice.json", R"({"light": {"intensity": 1, "intensity": 2}})") + out, "",
         "twice.json: the key 'intensity' appears twice in 'light'"},
    };
    for (const BadInput& c : cases) {
        const auto start = std::chrono::steady_clock::now();
        Result r = run(c.arguments, c.environment);
        EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
        EXPECT_EQ(r.status, 2) << c.arguments << "\n" << r.output;
        EXPECT_NE(r.output.find("error: "), std::string::npos) << c.arguments << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos)
            << "'" << c.expected << "' not named for: " << c.arguments << "\n"
            << r.output;
        EXPECT_FALSE(fs::exists(dir / "bad.png")) << c.arguments;
        EXPECT_FALSE(fs::exists(dir / "bad.exr")) << c.arguments;
    }
    expectNoTemporaries();
}

} // namespace
