// The README's bad-input table, beyond what test_scene (the loader's messages) and test_cli
// (render's options) already check: malformed, truncated and hostile glTF and scene files,
// non-finite and overflowing numbers, degenerate and empty geometry, missing textures,
// unsupported glTF features, absurd settings and sizes, no Vulkan device. Each case gets an
// error naming the problem or its documented fallback, never a crash, never a half-written file.
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

namespace {

// The binary chunk of a one-mesh glTF: float positions, then 32-bit indices.
std::string meshBytes(const std::vector<float>& positions, const std::vector<uint32_t>& indices) {
    std::string bytes(positions.size() * 4 + indices.size() * 4, '\0');
    std::memcpy(bytes.data(), positions.data(), positions.size() * 4);
    std::memcpy(bytes.data() + positions.size() * 4, indices.data(), indices.size() * 4);
    return bytes;
}

// The JSON of that glTF: one indexed triangle list in node 0 of scene 0.
json meshJson(size_t positionCount, size_t indexCount) {
    const size_t positionBytes = positionCount * 4, indexBytes = indexCount * 4;
    auto accessor = [](int view, int type, size_t count, const char* shape) {
        return json{
            {"bufferView", view}, {"componentType", type}, {"count", count}, {"type", shape}};
    };
    return {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
        {"buffers", {{{"byteLength", positionBytes + indexBytes}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteLength", positionBytes}},
          {{"buffer", 0}, {"byteOffset", positionBytes}, {"byteLength", indexBytes}}}},
        {"accessors",
         {accessor(0, 5126, positionCount / 3, "VEC3"), accessor(1, 5125, indexCount, "SCALAR")}}};
}

// GLB container: 12-byte header, JSON chunk (space padded), BIN chunk (zero padded).
std::string glb(const std::string& text, std::string bin) {
    const std::string padded = text + std::string((4 - text.size() % 4) % 4, ' ');
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const uint32_t length = uint32_t(28 + padded.size() + bin.size());
    return "glTF" + u32(2) + u32(length) + u32(uint32_t(padded.size())) + "JSON" + padded +
           u32(uint32_t(bin.size())) + "BIN" + std::string(1, '\0') + bin;
}
std::string meshGlb(const std::vector<float>& positions, const std::vector<uint32_t>& indices) {
    return glb(meshJson(positions.size(), indices.size()).dump(), meshBytes(positions, indices));
}
const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

class BadInput : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("ssgi-bad-input-" + std::to_string(getpid()) + "-" +
                                            std::to_string(std::random_device()()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string write(const std::string& name, const std::string& bytes) const {
        std::ofstream(dir_ / name, std::ios::binary) << bytes;
        return (dir_ / name).string();
    }
    // The message of the InputError loading `path` throws; fails the test when it loads.
    static std::string loadError(const std::string& path) {
        try {
            loadScene(path);
        } catch (const InputError& error) {
            return error.what();
        }
        ADD_FAILURE() << path << " loaded; an InputError was expected";
        return "";
    }
    fs::path dir_;
};

// Each hostile glTF is the one-triangle file changed by JSON-patch "add" steps ([path, value]:
// sets an object's member, inserts into an array, "-" appends), and what its error must say.
#define SPOT                                                                                       \
    R"(["/extensions",{"KHR_lights_punctual":{"lights":[{"type":"spot","spot":{"outerConeAngle":0.5}}]}}],["/nodes/-",{"extensions":{"KHR_lights_punctual":{"light":0}}}],["/scenes/0/nodes/-",1])"
const char* const kGltfCases[][3] = {
    {"count-past-view", R"([["/accessors/0/count", 4]])", "run past the end"},
    {"index-count", R"([["/accessors/1/count", 2]])", "not a multiple of 3"},
    {"vec2-positions", R"([["/accessors/0/type", "VEC2"]])", "expected VEC3"},
    {"int-positions", R"([["/accessors/0/componentType", 5125]])", "component type 5125"},
    {"sparse", R"([["/accessors/0/sparse", {"count": 1}]])", "sparse"},
    {"translation-overflow", R"([["/nodes/0/translation", [1e39, 0, 0]]])", "not finite"},
    {"number-overflow", R"([["/nodes/0/translation", [1e300, 0, 0]]])", "number overflow"},
    {"world-overflow",
     R"([["/nodes/0/scale", [1e30, 1e30, 1e30]], ["/nodes/-", {"scale": [1e30, 1e30, 1e30], "children": [0]}], ["/scenes/0/nodes", [1]]])",
     "world transform is not finite"},
    {"far-away", R"([["/nodes/0/scale", [1e11, 1, 1]]])", "beyond 1e10"},
    {"cycle", R"([["/nodes/0/children", [0]]])", "its own ancestor"},
    {"two-parents", R"([["/nodes/-", {"children": [0]}], ["/scenes/0/nodes/-", 1]])",
     "more than one parent"},
    {"camera-zero-scale",
     R"([["/cameras", [{"type": "perspective", "perspective": {"yfov": 1, "znear": 1}}]], ["/nodes/-", {"camera": 0, "scale": [0, 0, 0]}], ["/scenes/0/nodes/-", 1]])",
     "no view direction"},
    {"light-zero-scale", "[" SPOT R"(, ["/nodes/1/scale", [0, 0, 0]]])", "no direction"},
    {"light-cone-zero",
     "[" SPOT R"(, ["/extensions/KHR_lights_punctual/lights/0/spot/outerConeAngle", 0]])",
     "outerConeAngle must be > 0"},
    {"light-too-bright",
     "[" SPOT R"(, ["/extensions/KHR_lights_punctual/lights/0/intensity", 1e30]])",
     "intensity in [0, 1e12]"},
    // The index was converted to int before it was checked: undefined behaviour (UBSan).
    {"light-index", "[" SPOT R"(, ["/nodes/1/extensions/KHR_lights_punctual/light", 1e20]])",
     "light 1e+20 does not exist"},
    {"negative-albedo",
     R"([["/materials", [{"pbrMetallicRoughness": {"baseColorFactor": [-1, 0, 0, 1]}}]], ["/meshes/0/primitives/0/material", 0]])",
     "baseColorFactor must be finite and not negative"},
    {"missing-texture",
     R"([["/images", [{"uri": "textures/missing.png"}]], ["/textures", [{"source": 0}]], ["/materials", [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]], ["/meshes/0/primitives/0/material", 0]])",
     "textures/missing.png"},
    {"corrupt-texture", R"([["/images", [{"uri": "data:image/png;base64,iVBORw0KGgoAAAA"}]]])",
     "image"},
    {"required-extension", R"([["/extensionsRequired", ["KHR_draco_mesh_compression"]]])",
     "KHR_draco_mesh_compression"},
    {"no-nodes", R"([["/scenes/0/nodes", []]])", "no triangles"},
    {"only-points", R"([["/meshes/0/primitives/0/mode", 0]])", "no triangles"},
};

TEST_F(BadInput, MalformedGltfNamesTheFileAndTheProblem) {
    const std::string bin = meshBytes(kTriangle, {0, 1, 2});
    for (const auto& [name, steps, expected] : kGltfCases) {
        SCOPED_TRACE(name);
        json patch = json::array();
        for (const json& step : json::parse(steps))
            patch.push_back({{"op", "add"}, {"path", step[0]}, {"value", step[1]}});
        std::string text = meshJson(9, 3).patch(patch).dump();
        // JSON holds no inf: a number beyond double range is how a file says it.
        for (size_t at; (at = text.find("1e+300")) != std::string::npos;)
            text.replace(at, 6, "1e999");
        const std::string message = loadError(write(name + std::string(".glb"), glb(text, bin)));
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find(expected), std::string::npos) << message;
    }
    // A chain 5000 deep overflowed the stack (found with the fuzzer's sanitizer build).
    json deep = meshJson(9, 3);
    for (int i = 1; i <= 5000; ++i)
        deep["nodes"].push_back({{"children", {i - 1}}});
    deep["scenes"][0]["nodes"] = {5000};
    EXPECT_NE(loadError(write("deep.glb", glb(deep.dump(), bin))).find("more than 1000 levels"),
              std::string::npos);
}

TEST_F(BadInput, NonFiniteAndCollapsedPositions) {
    EXPECT_NE(loadError(write("inf.glb", meshGlb({0, 0, 0, INFINITY, 0, 0, 0, 1, 0}, {0, 1, 2})))
                  .find("POSITION 1 is not a finite number"),
              std::string::npos);
    EXPECT_NE(loadError(write("index.glb", meshGlb(kTriangle, {0, 1, 0xffffffffu})))
                  .find("index 4294967295 (entry 2) is out of range"),
              std::string::npos);
    EXPECT_NE(loadError(write("point.glb", meshGlb(std::vector<float>(9, 1.0f), {0, 1, 2})))
                  .find("all of the scene is at one point"),
              std::string::npos);
}

TEST_F(BadInput, AFolderIsNotASceneFile) {
    fs::create_directories(dir_ / "folder.json");
    EXPECT_NE(loadError((dir_ / "folder.json").string()).find("not a regular file"),
              std::string::npos);
}

// A .gltf whose buffer is an external file: each URI resolves against the glTF's own folder
// (`..` allowed), never the working directory; absolute paths and other schemes are refused, and
// so is anything but a regular file, without opening it (a FIFO hung the loader, /dev/zero
// filled the memory until std::bad_alloc).
TEST_F(BadInput, ExternalUrisResolveBesideTheGltfAndOnlyToRegularFiles) {
    const std::string bin = meshBytes(kTriangle, {0, 1, 2});
    fs::create_directories(dir_ / "models");
    fs::create_directories(dir_ / "shared");
    fs::create_directories(dir_ / "cwd");
    fs::create_directories(dir_ / "models" / "folder.bin");
    ASSERT_EQ(mkfifo((dir_ / "models" / "fifo.bin").c_str(), 0600), 0);
    write("shared/mesh.bin", bin);
    write("cwd/only-in-cwd.bin", bin);
    auto gltfWith = [&](const std::string& uri) {
        json g = meshJson(9, 3);
        g["buffers"][0]["uri"] = uri;
        return write("models/m.gltf", g.dump());
    };
    const fs::path saved = fs::current_path();
    fs::current_path(dir_ / "cwd"); // where tinygltf used to look second
    std::string up;
    for (int i = 0; i < 12; ++i)
        up += "../";
    const char* const cases[][2] = {
        {"only-in-cwd.bin", "only-in-cwd.bin"},         {"folder.bin", "'folder.bin' is a folder"},
        {"fifo.bin", "'fifo.bin' is a FIFO"},           {"/dev/zero", "is an absolute path"},
        {"file:///dev/zero", "is not a relative path"},
    };
    for (const auto& [uri, expected] : cases) {
        SCOPED_TRACE(uri);
        const auto start = std::chrono::steady_clock::now();
        const std::string message = loadError(gltfWith(uri));
        EXPECT_NE(message.find("m.gltf"), std::string::npos) << message;
        EXPECT_NE(message.find(expected), std::string::npos) << message;
        EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
    }
    for (const char* device : {"dev/zero", "dev/stdin", "dev/null"}) {
        SCOPED_TRACE(device);
        const std::string message = loadError(gltfWith(up + device));
        EXPECT_NE(message.find(", not a regular file"), std::string::npos) << message;
    }
    fs::current_path(saved);
    Scene scene;
    EXPECT_NO_THROW(scene = loadScene(gltfWith("../shared/mesh.bin"), {{"ground_plane", 0}}));
    EXPECT_EQ(scene.instances.size(), 1u);
    EXPECT_NO_THROW(loadScene(gltfWith("..%2Fshared%2Fmesh.bin"))); // percent-encoded as well
}

// Every prefix of a GLB and of a scene file is rejected with an InputError; none crashes.
TEST_F(BadInput, EveryTruncationIsAnError) {
    const std::string whole = meshGlb(kTriangle, {0, 1, 2});
    ASSERT_NO_THROW(loadScene(write("whole.glb", whole)));
    for (size_t n = 0; n < whole.size(); ++n)
        EXPECT_THROW(loadScene(write("cut.glb", whole.substr(0, n))), InputError) << n << " bytes";
    std::string header = whole;
    header[11] = char(0x7f); // a total length far beyond the file
    EXPECT_THROW(loadScene(write("length.glb", header)), InputError);
    std::ifstream in(test::sourcePath("scenes/cornell-box.json"));
    const std::string scene(std::istreambuf_iterator<char>(in), {});
    for (size_t n = 0; n < scene.rfind('}'); ++n)
        EXPECT_THROW(loadScene(write("cut.json", scene.substr(0, n))), InputError) << n << " bytes";
    std::ifstream model(test::sceneModel("cornell-box.glb"), std::ios::binary);
    const std::string bytes(std::istreambuf_iterator<char>(model), {});
    for (size_t n = 0; n + 1 < bytes.size(); n += 61)
        EXPECT_THROW(loadScene(write("shared.glb", bytes.substr(0, n))), InputError) << n;
}

// Each tests/scenes/bad-*.json says in its "description" what its error must contain.
TEST_F(BadInput, SceneFilesInTestsScenes) {
    size_t count = 0;
    for (const auto& entry : fs::directory_iterator(test::sourcePath("tests/scenes"))) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("bad-", 0) != 0 || entry.path().extension() != ".json") continue;
        SCOPED_TRACE(name);
        std::ifstream in(entry.path());
        const std::string text(std::istreambuf_iterator<char>(in), {});
        std::smatch expected;
        ASSERT_TRUE(std::regex_search(text, expected, std::regex("\"expect: ([^\"]*)\"")));
        const std::string message = loadError(entry.path().string());
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find(expected[1].str()), std::string::npos) << message;
        ++count;
    }
    EXPECT_GE(count, 10u);
}

// What the renderer does not use loads with one warning per kind, however often it occurs.
TEST_F(BadInput, UnsupportedGltfFeaturesWarnOnce) {
    json g = meshJson(9, 3);
    auto& primitives = g["meshes"][0]["primitives"];
    primitives[0]["targets"] = {{{"POSITION", 0}}};
    for (int copy = 0; copy < 2; ++copy)
        primitives.push_back({{"attributes", {{"POSITION", 0}}}, {"mode", 1}});
    g["nodes"].push_back({{"mesh", 0}, {"translation", {0, 0, 1}}, {"camera", 0}});
    g["nodes"][0]["camera"] = 0;
    g["scenes"][0]["nodes"].push_back(1);
    g["skins"] = {{{"joints", {0}}}, {{"joints", {1}}}};
    g["animations"] = {{{"channels", json::array()}, {"samplers", json::array()}}};
    g["cameras"] = {{{"type", "orthographic"},
                     {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 9}}}}};
    std::ostringstream said;
    std::streambuf* saved = std::cerr.rdbuf(said.rdbuf());
    Scene scene;
    EXPECT_NO_THROW(
        scene = loadScene(write("features.glb", glb(g.dump(), meshBytes(kTriangle, {0, 1, 2}))),
                          {{"ground_plane", 0}})); // the file's own instances
    std::cerr.rdbuf(saved);
    EXPECT_EQ(scene.instances.size(), 2u); // the triangles of both nodes, not the lines
    const std::string text = said.str();
    for (const char* warning :
         {"skins are ignored", "animations are ignored", "morph targets are ignored",
          "mode 1 (points or lines)", "orthographic cameras are ignored"}) {
        const size_t first = text.find(warning);
        EXPECT_NE(first, std::string::npos) << warning << " not in:\n" << text;
        EXPECT_EQ(text.find(warning, first + 1), std::string::npos) << warning << " twice";
    }
}

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

class BadInputOnDevice : public test::VulkanTest {};

// Zero-area and collinear triangles load (made-up flat normals) and render cleanly.
TEST_F(BadInputOnDevice, DegenerateTrianglesRender) {
    const std::string path =
        (fs::temp_directory_path() / ("ssgi-degenerate-" + std::to_string(getpid()) + ".glb"));
    const std::vector<float> positions = {-1, 0, -1, 1, 0, -1, 1, 0, 1,  // a floor triangle
                                          0,  1, 0,  0, 1, 0,  0, 1, 0,  // one point
                                          0,  1, 0,  1, 1, 0,  2, 1, 0}; // one line
    std::ofstream(path, std::ios::binary) << meshGlb(positions, {0, 1, 2, 3, 4, 5, 6, 7, 8});
    const Scene scene = loadScene(path);
    fs::remove(path);
    for (const Vertex& v : scene.meshes[0].vertices)
        EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
    const test::Frame frame = test::render(scene, 48, 48);
    for (float value : frame.hdr)
        ASSERT_TRUE(std::isfinite(value));
}

// The Cornell box, its camera and its light moved 1e3 units along every axis render as they do
// at the origin (they gave relMSE 0.16 before the renderer moved everything next to the GPU's
// origin); 1e5 units away, where the scene model's floats round the coordinates themselves,
// loading says so.
TEST_F(BadInputOnDevice, FarFromTheOrigin) {
    std::ifstream in(test::sourcePath("scenes/cornell-box.json"));
    const json original = json::parse(in);
    auto shifted = [&](double offset) {
        json scene = original;
        scene.erase("camera_path");
        std::function<void(json&)> shift = [&](json& value) {
            if (value.is_array() && value.size() == 3 && value[0].is_number())
                for (json& c : value)
                    c = c.get<double>() + offset;
            else if (value.is_array())
                for (json& element : value)
                    shift(element);
        };
        for (json& object : scene["objects"])
            for (const char* key : {"corners", "center"})
                if (object.contains(key)) shift(object[key]);
        shift(scene["light"]["position"]);
        shift(scene["camera"]["position"]);
        shift(scene["camera"]["target"]);
        const std::string path =
            (fs::temp_directory_path() /
             ("ssgi-far-" + std::to_string(getpid()) + "-" + std::to_string(int(offset)) + ".json"))
                .string();
        std::ofstream(path) << scene.dump();
        return path;
    };
    auto load = [](const std::string& path, std::string& said) {
        std::ostringstream capture;
        std::streambuf* saved = std::cerr.rdbuf(capture.rdbuf());
        Scene scene = loadScene(path);
        std::cerr.rdbuf(saved);
        fs::remove(path);
        said = capture.str();
        return scene;
    };
    std::string said;
    const Scene atOrigin = load(shifted(0.0), said);
    EXPECT_EQ(said, "");
    const Scene away = load(shifted(1e3), said);
    EXPECT_EQ(said, "");
    load(shifted(1e5), said);
    EXPECT_NE(said.find("lies 1e+05 units from the origin"), std::string::npos) << said;
    const test::Frame a = test::render(atOrigin, 32, 32), b = test::render(away, 32, 32);
    double error = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < a.hdr.size(); ++i)
        if (i % 4 != 3) {
            const double d = a.hdr[i] - b.hdr[i];
            error += d * d / (double(a.hdr[i]) * a.hdr[i] + 1e-2);
            ++count;
        }
    EXPECT_LT(error / double(count), 1e-3);
}

// Sizes beyond the device's limits are input errors before anything is allocated.
TEST_F(BadInputOnDevice, BeyondTheDeviceLimits) {
    Scene scene = loadScene(test::sourcePath("tests/scenes/empty-box.json"));
    const uint32_t limit = test::context().properties.limits.maxImageDimension2D;
    EXPECT_THROW(Renderer(test::context(), scene, {1, limit + 1, "final"}), InputError);
    scene.settings.shadow_map_size = limit + 1.0; // past checkSetting, as a caller could
    EXPECT_THROW(Renderer(test::context(), scene, {16, 16, "final"}), InputError);
}
// An image size the device allows in each dimension but whose images its memory cannot hold
// says what it needs and what there is (it was the bare text of a failed vkBindImageMemory).
TEST_F(BadInputOnDevice, ImageSizeBeyondTheDeviceMemory) {
    const vk::Context& ctx = test::context();
    VkDeviceSize heap = 0;
    for (uint32_t h = 0; h < ctx.memoryProperties.memoryHeapCount; ++h)
        heap = std::max(heap, ctx.memoryProperties.memoryHeaps[h].size);
    const uint32_t limit = ctx.properties.limits.maxImageDimension2D;
    if (VkDeviceSize(limit) * limit * 16 <= heap)
        GTEST_SKIP() << "one 16-byte image of the largest size fits this device's memory";
    const Scene scene = loadScene(test::sourcePath("tests/scenes/empty-box.json"));
    try {
        Renderer renderer(test::context(), scene, {limit, limit, "final"});
        ADD_FAILURE() << "a " << limit << "x" << limit << " renderer was made";
    } catch (const InputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("MiB for each of the frame's"), std::string::npos) << message;
        EXPECT_NE(message.find("choose a smaller --size"), std::string::npos) << message;
    }
}

// A texture larger than the device's largest 2D image is refused before any image is made.
TEST_F(BadInputOnDevice, TextureBeyondTheDeviceLimit) {
    Scene scene = loadScene(test::sourcePath("tests/scenes/empty-box.json"));
    const uint32_t limit = test::context().properties.limits.maxImageDimension2D;
    scene.textures.push_back({"tall", 1, limit + 1, std::vector<uint8_t>((limit + 1) * 4, 255)});
    scene.materials[0].baseColorTexture = 0;
    EXPECT_THROW(Renderer(test::context(), scene, {16, 16, "final"}), InputError);
}

} // namespace
