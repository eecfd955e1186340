// The README's bad-input table, beyond what test_scene (the loader's messages) and test_cli
// (render's options) already check: malformed, truncated and hostile glTF and scene files,
// non-finite and overflowing numbers, degenerate and empty geometry, missing textures,
// unsupported glTF features, absurd settings and sizes, no Vulkan device. Each case gets an
// error naming the problem or its documented fallback, never a crash, never a half-written file.
#include "bad_input.h"
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
using namespace ssgi::test;

namespace {

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

} // namespace
