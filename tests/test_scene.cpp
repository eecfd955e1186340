// Scene loading: the default scene file, hand-written glTF files with known answers, and every
// kind of bad input the loader must reject with a useful message (the models of scenes/models/
// are in test_scene_models.cpp).
#include "scene/bare_model.h"
#include "scene/camera.h"
#include "scene/scene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace fs = std::filesystem;
using nlohmann::json;
using ssgi::InputError;
using ssgi::loadScene;
using ssgi::Scene;

namespace {

const std::string kSourceDir = SSGI_SOURCE_DIR;
const std::string kModels = kSourceDir + "/scenes/models/";

std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t group = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) group |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) group |= bytes[i + 2];
        for (size_t k = 0; k < 4; ++k)
            out += i + k <= bytes.size() ? digits[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

// A glTF with one indexed triangle-list mesh (no normals) in an embedded base64 buffer.
json triangleGltf(const std::vector<float>& positions, const std::vector<uint16_t>& indices,
                  const json& nodes, const json& rootNodes) {
    std::vector<uint8_t> bytes(positions.size() * 4 + indices.size() * 2);
    std::memcpy(bytes.data(), positions.data(), positions.size() * 4);
    std::memcpy(bytes.data() + positions.size() * 4, indices.data(), indices.size() * 2);
    const size_t positionBytes = positions.size() * 4;
    return {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", rootNodes}}}},
        {"nodes", nodes},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
        {"buffers",
         {{{"byteLength", bytes.size()},
           {"uri", "data:application/octet-stream;base64," + base64(bytes)}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", positionBytes}},
          {{"buffer", 0}, {"byteOffset", positionBytes}, {"byteLength", indices.size() * 2}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", positions.size() / 3},
           {"type", "VEC3"}},
          {{"bufferView", 1},
           {"componentType", 5123},
           {"count", indices.size()},
           {"type", "SCALAR"}}}},
    };
}

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

class SceneFiles : public ::testing::Test {
protected:
    void SetUp() override {
        std::random_device random;
        dir_ = fs::temp_directory_path() / ("ssgi_test_scene_" + std::to_string(random()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& text) const {
        const std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
    // Loading must fail with an InputError naming the file and every given detail.
    void expectInputError(const std::string& path, const std::vector<std::string>& details) {
        try {
            loadScene(path);
            ADD_FAILURE() << path << " loaded, expected an InputError";
        } catch (const InputError& error) {
            const std::string message = error.what();
            EXPECT_NE(message.find(fs::path(path).filename().string()), std::string::npos)
                << message;
            for (const std::string& detail : details)
                EXPECT_NE(message.find(detail), std::string::npos)
                    << "'" << detail << "' not in: " << message;
        }
    }
    // A scene file of one white quad plus `extra` top-level keys.
    std::string quadScene(const std::string& name, const json& extra) const {
        json scene = {{"materials", {{"white", {{"albedo", {0.8, 0.8, 0.8}}}}}},
                      {"objects",
                       {{{"type", "quad"},
                         {"material", "white"},
                         {"corners", {{1, 0, 0}, {0, 0, 0}, {0, 0, 1}, {1, 0, 1}}}}}}};
        scene.update(extra);
        return write(name, scene.dump());
    }

    fs::path dir_;
};

TEST(DefaultScene, CornellBoxLoadsAsWritten) {
    const Scene scene = loadScene(kSourceDir + "/scenes/cornell-box.json");
    EXPECT_EQ(scene.meshes.size(), 7u);
    EXPECT_EQ(scene.instances.size(), 7u);
    EXPECT_EQ(scene.materials.size(), 3u);
    EXPECT_NEAR(scene.bounds.min.x, 0.0f, 1e-6f);
    EXPECT_NEAR(scene.bounds.max.x, 0.556f, 1e-6f);
    EXPECT_NEAR(scene.bounds.min.y, 0.0f, 1e-6f);
    EXPECT_NEAR(scene.bounds.max.y, 0.5488f, 1e-6f);
    EXPECT_NEAR(scene.bounds.max.z, 0.5592f, 1e-6f);

    EXPECT_NEAR(glm::distance(scene.light.position, glm::vec3(0.278f, 0.5478f, 0.2795f)), 0, 1e-6);
    EXPECT_NEAR(glm::distance(scene.light.direction, glm::vec3(0, -1, 0)), 0, 1e-6);
    EXPECT_NEAR(glm::distance(scene.light.color, glm::vec3(1.0f, 0.85f, 0.6f)), 0, 1e-6);
    EXPECT_FLOAT_EQ(scene.light.intensity, 1.5f);
    EXPECT_NEAR(scene.light.outerConeAngle, glm::radians(70.0f), 1e-6);
    EXPECT_NEAR(scene.light.innerConeAngle, glm::radians(35.0f), 1e-6);
    EXPECT_FLOAT_EQ(scene.light.radius, 0.066f);

    EXPECT_NEAR(glm::distance(scene.camera.position, glm::vec3(0.278f, 0.273f, -0.8f)), 0, 1e-6);
    const glm::vec3 forward = scene.camera.orientation * glm::vec3(0, 0, -1);
    const glm::vec3 up = scene.camera.orientation * glm::vec3(0, 1, 0);
    EXPECT_NEAR(glm::distance(forward, glm::vec3(0, 0, 1)), 0, 1e-5);
    EXPECT_NEAR(glm::distance(up, glm::vec3(0, 1, 0)), 0, 1e-5);
    EXPECT_NEAR(scene.camera.yfov, glm::radians(39.3f), 1e-6);
    EXPECT_GT(scene.camera.znear, 0.0f);
    EXPECT_GT(scene.camera.zfar, glm::distance(scene.camera.position, scene.bounds.max));
    EXPECT_EQ(scene.sky.zenith, glm::vec3(0.0f));
}

TEST(DefaultScene, PrimitivesFaceOutwardWithUnitNormals) {
    const Scene scene = loadScene(kSourceDir + "/scenes/cornell-box.json");
    // The floor's corners run counter-clockwise seen from above, the ceiling's from below.
    EXPECT_NEAR(scene.meshes[0].vertices[0].normal.y, 1.0f, 1e-6f);
    EXPECT_NEAR(scene.meshes[1].vertices[0].normal.y, -1.0f, 1e-6f);
    for (size_t box : {5u, 6u}) {
        const ssgi::Mesh& mesh = scene.meshes[box];
        ASSERT_EQ(mesh.vertices.size(), 24u);
        ASSERT_EQ(mesh.indices.size(), 36u);
        glm::vec3 center(0.0f);
        for (const ssgi::Vertex& v : mesh.vertices)
            center += v.position / 24.0f;
        for (size_t t = 0; t < mesh.indices.size(); t += 3) {
            const glm::vec3 a = mesh.vertices[mesh.indices[t]].position;
            const glm::vec3 b = mesh.vertices[mesh.indices[t + 1]].position;
            const glm::vec3 c = mesh.vertices[mesh.indices[t + 2]].position;
            const glm::vec3 face = glm::normalize(glm::cross(b - a, c - a));
            EXPECT_GT(glm::dot(face, (a + b + c) / 3.0f - center), 0.0f);
            EXPECT_NEAR(glm::dot(face, mesh.vertices[mesh.indices[t]].normal), 1.0f, 1e-5f);
        }
    }
}

TEST_F(SceneFiles, NodeTransformsGiveWorldBounds) {
    // Root 0 is translated and has child 1, scaled by 2; root 2 is moved back in z.
    const json nodes = {{{"mesh", 0}, {"translation", {10, 0, 0}}, {"children", {1}}},
                        {{"mesh", 0}, {"scale", {2, 2, 2}}},
                        {{"mesh", 0}, {"translation", {0, 0, -3}}}};
    const std::string gltf =
        write("tiny.gltf", triangleGltf(kTriangle, {0, 1, 2}, nodes, {0, 2}).dump());
    const Scene scene = loadScene(gltf, {{"ground_plane", 0}}); // the file's geometry alone
    EXPECT_EQ(scene.meshes.size(), 1u); // one glTF mesh, instanced three times
    EXPECT_EQ(scene.instances.size(), 3u);
    EXPECT_NEAR(glm::distance(scene.bounds.min, glm::vec3(0, 0, -3)), 0, 1e-6);
    EXPECT_NEAR(glm::distance(scene.bounds.max, glm::vec3(12, 2, 0)), 0, 1e-6);
    EXPECT_EQ(scene.materials.size(), 1u); // the default material for a primitive without one

    const std::string scaled =
        write("scaled.json", json{{"gltf", "tiny.gltf"}, {"gltf_scale", 0.5}}.dump());
    const Scene half = loadScene(scaled);
    EXPECT_NEAR(glm::distance(half.bounds.min, glm::vec3(0, 0, -1.5f)), 0, 1e-6);
    EXPECT_NEAR(glm::distance(half.bounds.max, glm::vec3(6, 1, 0)), 0, 1e-6);

    // Each file's materials, then the scene file's, each block after the ones before it.
    const json twice = {
        {"gltf", {"tiny.gltf", "tiny.gltf"}},
        {"materials", {{"red", {{"albedo", {1, 0, 0}}}}}},
        {"objects",
         {{{"type", "sphere"}, {"material", "red"}, {"center", {0, 5, 0}}, {"radius", 1}}}}};
    const Scene both = loadScene(write("twice.json", twice.dump()));
    ASSERT_EQ(both.meshes.size(), 3u);
    for (int m = 0; m < 3; ++m)
        EXPECT_EQ(both.meshes[size_t(m)].material, m);
    EXPECT_EQ(both.materials[2].name, "red");
}

// Triangle strips and fans are triangles: the unit square drawn either way is two triangles of
// total area 1 facing +Z (the glTF winding rules keep every triangle counter-clockwise).
TEST_F(SceneFiles, TriangleStripsAndFansAreTriangles) {
    const std::vector<float> square = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const struct {
        int mode;
        std::vector<uint16_t> indices;
    } cases[] = {{5, {0, 1, 2, 3}}, {6, {0, 1, 3, 2}}, {5, {0, 1, 2, 3, 3, 2}}};
    for (const auto& [mode, indices] : cases) {
        SCOPED_TRACE("mode " + std::to_string(mode) + ", " + std::to_string(indices.size()));
        json gltf = triangleGltf(square, indices, {{{"mesh", 0}}}, {0});
        gltf["meshes"][0]["primitives"][0]["mode"] = mode;
        const Scene scene = loadScene(write("strip.gltf", gltf.dump()), {{"ground_plane", 0}});
        ASSERT_EQ(scene.meshes.size(), 1u);
        const ssgi::Mesh& mesh = scene.meshes[0];
        EXPECT_EQ(mesh.indices.size(), 3 * (indices.size() - 2));
        float area = 0.0f;
        for (size_t t = 0; t < mesh.indices.size(); t += 3) {
            const glm::vec3 a = mesh.vertices[mesh.indices[t]].position,
                            b = mesh.vertices[mesh.indices[t + 1]].position,
                            c = mesh.vertices[mesh.indices[t + 2]].position;
            const glm::vec3 doubled = glm::cross(b - a, c - a);
            area += 0.5f * glm::length(doubled);
            if (glm::length(doubled) > 0.0f) {
                EXPECT_GT(doubled.z, 0.0f) << "triangle " << t / 3;
            }
        }
        EXPECT_NEAR(area, 1.0f, 1e-6f);
    }
}

TEST_F(SceneFiles, GltfCameraAndSpotLightAreUsed) {
    // Node 2 is turned -90 degrees about X, which points its -Z (the light's axis) down.
    const json light = {{"KHR_lights_punctual", {{"light", 0}}}};
    json gltf = triangleGltf(kTriangle, {0, 1, 2},
                             {{{"mesh", 0}},
                              {{"camera", 0}, {"translation", {0, 0, 5}}},
                              {{"translation", {0, 4, 0}},
                               {"rotation", {-0.70710678, 0, 0, 0.70710678}},
                               {"extensions", light}}},
                             {0, 1, 2});
    gltf["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}};
    gltf["extensionsUsed"] = {"KHR_lights_punctual"};
    gltf["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "spot"}, {"intensity", 7}, {"spot", {{"outerConeAngle", 0.6}}}}};
    const Scene scene = loadScene(write("viewpoint.gltf", gltf.dump()));
    EXPECT_NEAR(glm::distance(scene.camera.position, glm::vec3(0, 0, 5)), 0, 1e-6);
    EXPECT_FLOAT_EQ(scene.camera.yfov, 0.5f);
    EXPECT_FLOAT_EQ(scene.camera.znear, 0.1f);
    EXPECT_GT(scene.camera.zfar, 5.0f); // glTF's "infinite" far plane fitted to the bounds
    EXPECT_NEAR(glm::distance(scene.light.position, glm::vec3(0, 4, 0)), 0, 1e-6);
    EXPECT_NEAR(glm::distance(scene.light.direction, glm::vec3(0, -1, 0)), 0, 1e-5);
    EXPECT_FLOAT_EQ(scene.light.intensity, 7.0f);
    EXPECT_FLOAT_EQ(scene.light.outerConeAngle, 0.6f);
}

TEST_F(SceneFiles, MissingFile) {
    expectInputError((dir_ / "no-such-scene.json").string(), {"not found"});
}
TEST_F(SceneFiles, MalformedJson) {
    expectInputError(write("broken.json", "{\"camera\": {\"position\": [0, 1, 2],"),
                     {"malformed JSON", "byte"});
}
TEST_F(SceneFiles, BadKeysAndValues) {
    struct Case {
        const char* file;
        json keys; // added to a valid scene
        std::string detail;
    };
    const Case cases[] = {
        {"camra.json", {{"camra", json::object()}}, "unknown key 'camra' at top level"},
        {"colour.json", {{"light", {{"colour", {1, 1, 1}}}}}, "unknown key 'colour' in 'light'"},
        {"type.json", {{"light", {{"intensity", "bright"}}}}, "'light.intensity' must be a number"},
        {"length.json", {{"camera", {{"position", {0, 1}}}}}, "'camera.position' must be an array"},
        {"cone.json", {{"light", {{"cone_deg", 95}}}}, "'light.cone_deg' is 95"},
        {"setting.json",
         {{"settings", {{"shadow_map_sise", 512}}}},
         "unknown setting 'shadow_map_sise'"},
        {"size.json", {{"settings", {{"shadow_map_size", 0}}}}, "'shadow_map_size' is 0"},
    };
    for (const Case& bad : cases) {
        SCOPED_TRACE(bad.file);
        expectInputError(quadScene(bad.file, bad.keys), {bad.detail});
    }
}
// A key said twice in one object was silently the last one said.
TEST_F(SceneFiles, DuplicateKeysAreAnError) {
    expectInputError(write("dup-light.json", R"({"light": {"intensity": 1, "intensity": 2}})"),
                     {"'intensity' appears twice in 'light'"});
    expectInputError(write("dup-top.json", R"({"sky": {}, "sky": {"color": [1, 1, 1]}})"),
                     {"'sky' appears twice in the top-level object"});
    expectInputError(write("dup-object.json", R"({"objects": [{"type": "quad", "type": "box"}]})"),
                     {"'type' appears twice in 'objects[]'"});
    // The same key in different objects is no duplicate.
    EXPECT_NO_THROW(loadScene(quadScene(
        "same-key.json", {{"light", {{"intensity", 2}}}, {"camera", {{"yfov_deg", 40}}}})));
}

TEST_F(SceneFiles, UnknownMaterialName) {
    json scene = json::parse(std::ifstream(quadScene("tmp.json", json::object())));
    scene["objects"][0]["material"] = "chrome";
    expectInputError(write("material.json", scene.dump()), {"'objects[0].material'", "chrome"});
}
TEST_F(SceneFiles, UnsupportedExtension) {
    expectInputError(write("scene.txt", "{}"), {"unsupported file type"});
}
TEST_F(SceneFiles, SettingsAreKept) {
    const Scene scene =
        loadScene(quadScene("ok.json", {{"settings", {{"shadow_map_size", 2048}}}}));
    EXPECT_EQ(scene.settings.shadow_map_size, 2048);
    EXPECT_EQ(scene.settings.exposure, ssgi::Settings{}.exposure); // the default
}
TEST_F(SceneFiles, TruncatedGlb) {
    const std::string bunny = kModels + "bunny.glb";
    if (!fs::exists(bunny)) GTEST_SKIP() << bunny << " is not there";
    std::string bytes(1000, '\0');
    std::ifstream(bunny, std::ios::binary).read(bytes.data(), 1000);
    expectInputError(write("truncated.glb", bytes), {});
}
TEST_F(SceneFiles, IndexOutOfRange) {
    const json gltf = triangleGltf(kTriangle, {0, 1, 7}, {{{"mesh", 0}}}, {0});
    expectInputError(write("index.gltf", gltf.dump()), {"index 7", "out of range"});
}
TEST_F(SceneFiles, NanPosition) {
    const json gltf = triangleGltf({0, 0, 0, NAN, 0, 0, 0, 1, 0}, {0, 1, 2}, {{{"mesh", 0}}}, {0});
    expectInputError(write("nan.gltf", gltf.dump()), {"POSITION 1", "not a finite number"});
}
TEST_F(SceneFiles, GltfThatIsNotJson) {
    expectInputError(write("garbage.gltf", "this is not a glTF file at all"), {});
}
TEST_F(SceneFiles, MissingGltfNamesBothFiles) {
    expectInputError(write("refers.json", json{{"gltf", "absent.glb"}}.dump()),
                     {"absent.glb", "not found"});
}

// A bare model (no scene file) is staged: the tests below use a box standing clear of the
// origin, alone or on a floor of its own, at scales from millimetres to kilometres.

// A box over [-1, 1] x [0.5, 2] x [-0.5, 0.5] (12 triangles); with `floor`, also a 6 x 6 quad
// facing up at its base, which is then the lowest level of the model.
json boxGltf(bool floor, const json& node) {
    std::vector<float> positions;
    for (int corner = 0; corner < 8; ++corner)
        positions.insert(positions.end(), {corner & 1 ? 1.0f : -1.0f, corner & 2 ? 2.0f : 0.5f,
                                           corner & 4 ? 0.5f : -0.5f});
    // Wound counter-clockwise seen from outside: the base faces down.
    std::vector<uint16_t> indices = {0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1,
                                     4, 5, 7, 4, 7, 6, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
    if (floor) {
        positions.insert(positions.end(), {-3, 0.5f, -3, 3, 0.5f, -3, 3, 0.5f, 3, -3, 0.5f, 3});
        indices.insert(indices.end(), {8, 10, 9, 8, 11, 10});
    }
    return triangleGltf(positions, indices, json::array({node}), {0});
}

bool isGround(const ssgi::Instance& instance) {
    return instance.name == "ground";
}

// The bounds of the model's own instances (without the ground plane).
ssgi::Aabb modelBounds(const Scene& scene) {
    ssgi::Aabb bounds;
    for (const ssgi::Instance& instance : scene.instances)
        if (!isGround(instance))
            for (const ssgi::Vertex& v : scene.meshes[size_t(instance.mesh)].vertices)
                bounds.extend(glm::vec3(instance.transform * glm::vec4(v.position, 1.0f)));
    return bounds;
}

bool inside(glm::vec3 p, const ssgi::Aabb& bounds) {
    return glm::all(glm::greaterThanEqual(p, bounds.min)) &&
           glm::all(glm::lessThanEqual(p, bounds.max));
}

glm::vec3 corner(const ssgi::Aabb& bounds, int index) {
    return {index & 1 ? bounds.max.x : bounds.min.x, index & 2 ? bounds.max.y : bounds.min.y,
            index & 4 ? bounds.max.z : bounds.min.z};
}

TEST_F(SceneFiles, BareModelIsFramedAndLitAtEveryScale) {
    float firstIrradiance = 0.0f;
    for (float scale : {1e-3f, 1.0f, 1e3f}) {
        SCOPED_TRACE(scale);
        const json node = {{"mesh", 0},
                           {"scale", {scale, scale, scale}},
                           {"translation", {3 * scale, -scale, 2 * scale}}};
        const Scene scene = loadScene(write("box.gltf", boxGltf(false, node).dump()));
        const ssgi::Aabb model = modelBounds(scene);
        const glm::vec3 center = model.center();
        const float radius = 0.5f * glm::length(model.size());

        // The light is outside the model, aimed at its centre, with the whole model inside its
        // full-intensity cone, above the camera and on its side of the model.
        const ssgi::SpotLight& light = scene.light;
        EXPECT_FALSE(inside(light.position, model));
        EXPECT_GT(glm::distance(light.position, center), radius);
        EXPECT_GT(glm::dot(light.direction, glm::normalize(center - light.position)), 0.99999f);
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 toCorner = glm::normalize(corner(model, c) - light.position);
            EXPECT_LE(std::acos(std::min(glm::dot(toCorner, light.direction), 1.0f)),
                      light.innerConeAngle + 1e-3f);
        }
        EXPECT_LT(light.outerConeAngle, glm::radians(89.0f));
        EXPECT_GT(light.position.y, scene.camera.position.y);
        const glm::vec3 lightSide = light.position - center,
                        cameraSide = scene.camera.position - center;
        EXPECT_GT(lightSide.x * cameraSide.x + lightSide.z * cameraSide.z, 0.0f);
        // The same irradiance at the centre whatever the units: intensity follows distance^2.
        const float irradiance =
            light.intensity / glm::dot(center - light.position, center - light.position);
        EXPECT_NEAR(irradiance, ssgi::kBareModelIrradiance, 1e-3f);
        if (firstIrradiance == 0.0f) firstIrradiance = irradiance;
        EXPECT_NEAR(irradiance, firstIrradiance, 1e-4f * firstIrradiance);

        // The camera is outside the model, looks down at it, has its centre in the middle of
        // the frame and every corner of its bounds within the frame.
        const ssgi::Camera& camera = scene.camera;
        EXPECT_FALSE(inside(camera.position, model));
        EXPECT_LT((camera.orientation * glm::vec3(0, 0, -1)).y, -0.3f);
        const glm::mat4 viewProjection =
            ssgi::projectionMatrix(camera, 1.0f) * ssgi::viewMatrix(camera);
        glm::vec3 projected;
        ASSERT_TRUE(ssgi::projectToTexture(viewProjection, center, projected));
        EXPECT_NEAR(projected.x, 0.5f, 1e-3f);
        EXPECT_NEAR(projected.y, 0.5f, 1e-3f);
        float widest = 0.0f;
        for (int c = 0; c < 8; ++c) {
            ASSERT_TRUE(ssgi::projectToTexture(viewProjection, corner(model, c), projected));
            EXPECT_GT(projected.z, 0.0f);
            EXPECT_LT(projected.z, 1.0f);
            const float fromMiddle =
                std::max(std::abs(projected.x - 0.5f), std::abs(projected.y - 0.5f));
            EXPECT_LE(fromMiddle, 0.5f);
            widest = std::max(widest, fromMiddle);
        }
        EXPECT_GT(widest, 0.4f) << "the model fills most of the frame";

        // A daylight sky, and a ground plane under the model and around it, facing up.
        EXPECT_GT(scene.sky.horizon.b, 0.1f);
        EXPECT_GT(scene.sky.zenith.b, scene.sky.zenith.r);
        const auto ground = std::find_if(scene.instances.begin(), scene.instances.end(), isGround);
        ASSERT_NE(ground, scene.instances.end());
        ssgi::Aabb plane;
        for (const ssgi::Vertex& v : scene.meshes[size_t(ground->mesh)].vertices) {
            plane.extend(v.position);
            EXPECT_GT(v.normal.y, 0.999f);
        }
        EXPECT_LE(plane.max.y, model.min.y);
        EXPECT_GT(plane.max.y, model.min.y - 0.01f * radius);
        EXPECT_LT(plane.min.x, model.min.x - 2 * radius);
        EXPECT_GT(plane.max.z, model.max.z + 2 * radius);
        EXPECT_TRUE(inside(plane.min, scene.bounds) && inside(plane.max, scene.bounds));
        // The AO radius stays the model's, not the ground's.
        EXPECT_NEAR(ssgi::aoRadius(scene), 0.05f * glm::length(model.size()),
                    1e-4f * glm::length(model.size()));
    }
}

TEST_F(SceneFiles, GroundPlaneOnlyWhereTheModelHasNoFloor) {
    auto grounds = [](const Scene& scene) {
        return std::count_if(scene.instances.begin(), scene.instances.end(), isGround);
    };
    const std::string box = write("box.gltf", boxGltf(false, {{"mesh", 0}}).dump());
    const std::string onFloor = write("floor.gltf", boxGltf(true, {{"mesh", 0}}).dump());
    EXPECT_EQ(grounds(loadScene(box)), 1);
    EXPECT_EQ(grounds(loadScene(onFloor)), 0) << "its own floor spans its footprint";
    // The setting turns it off (given as `render --set` gives it, while loading).
    const Scene off = loadScene(box, {{"ground_plane", 0}});
    EXPECT_EQ(grounds(off), 0);
    EXPECT_NEAR(off.bounds.min.y, 0.5f, 1e-6f);
    EXPECT_THROW(ssgi::checkSetting("--set", "ground_plane", 2), InputError);

    // A base facing up counts as a floor when it covers half the footprint, not less.
    Scene scene;
    scene.meshes.push_back({{{{-1, 0, -1}, {0, 1, 0}, {}},
                             {{1, 0, -1}, {0, 1, 0}, {}},
                             {{1, 0, 1}, {0, 1, 0}, {}},
                             {{-1, 0, 1}, {0, 1, 0}, {}},
                             {{4, 4, 4}, {0, 1, 0}, {}}},
                            {0, 2, 1, 0, 3, 2, 0, 1, 4},
                            0});
    scene.instances.push_back({0, glm::mat4(1.0f), ""});
    ssgi::Aabb bounds;
    for (const ssgi::Vertex& v : scene.meshes[0].vertices)
        bounds.extend(v.position);
    EXPECT_FALSE(ssgi::hasGround(scene, bounds)); // base 4 of a 5 x 5 footprint
    scene.meshes[0].vertices[4].position = {1.5f, 4, 1.5f};
    bounds = {};
    for (const ssgi::Vertex& v : scene.meshes[0].vertices)
        bounds.extend(v.position);
    EXPECT_TRUE(ssgi::hasGround(scene, bounds)); // base 4 of a 2.5 x 2.5 footprint
}

TEST_F(SceneFiles, SceneFilesGetNoBareModelStaging) {
    // A scene file without light, camera or sky keeps the light straight down from inside the
    // top of its bounds, the camera on +Z, a black sky and no ground, as before.
    write("box.gltf", boxGltf(false, {{"mesh", 0}}).dump());
    const Scene scene = loadScene(write("box.json", json{{"gltf", "box.gltf"}}.dump()));
    EXPECT_EQ(std::count_if(scene.instances.begin(), scene.instances.end(), isGround), 0);
    EXPECT_NEAR(glm::distance(scene.light.direction, glm::vec3(0, -1, 0)), 0, 1e-6);
    EXPECT_LT(scene.light.position.y, scene.bounds.max.y);
    EXPECT_NEAR(scene.camera.position.x, 0.0f, 1e-6f);
    EXPECT_EQ(scene.sky.zenith, glm::vec3(0.0f));
    EXPECT_EQ(scene.settings.ao_radius, 0.0);
    // A scene file gets a ground plane by asking for one.
    const Scene asked = loadScene(write(
        "ground.json", json{{"gltf", "box.gltf"}, {"settings", {{"ground_plane", 1}}}}.dump()));
    EXPECT_EQ(std::count_if(asked.instances.begin(), asked.instances.end(), isGround), 1);
    EXPECT_EQ(asked.sky.zenith, glm::vec3(0.0f));
}

TEST_F(SceneFiles, BareModelLightFollowsItsGltfCamera) {
    // The file's camera looks at the box from -X; the default light comes from that side.
    json gltf = boxGltf(false, {{"mesh", 0}});
    gltf["nodes"].push_back({{"camera", 0},
                             {"translation", {-8, 1.25, 0}},
                             {"rotation", {0, -0.70710678, 0, 0.70710678}}});
    gltf["scenes"][0]["nodes"].push_back(1);
    gltf["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}};
    const Scene scene = loadScene(write("camera.gltf", gltf.dump()));
    EXPECT_NEAR(glm::distance(scene.camera.position, glm::vec3(-8, 1.25, 0)), 0, 1e-5);
    EXPECT_NEAR(glm::distance(scene.camera.orientation * glm::vec3(0, 0, -1), glm::vec3(1, 0, 0)),
                0, 1e-5);
    EXPECT_LT(scene.light.position.x, -1.0f);
    EXPECT_GT(glm::dot(scene.light.direction,
                       glm::normalize(modelBounds(scene).center() - scene.light.position)),
              0.99999f);
}

} // namespace
