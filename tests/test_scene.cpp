// Scene loading: the default scene file, hand-written glTF files with known answers, and every
// kind of bad input the loader must reject with a useful message (bare models are in
// test_bare_models.cpp, the models of scenes/models/ in test_scene_models.cpp).
#include "scene_files.h"

namespace {

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

} // namespace
