// The test models (scenes/models/): each loads bare with the triangle count its README
// gives, and with sane bounds, light, camera, indices and normals; the Cornell box without
// normals is flat-shaded, Sponza brings its textures; every scene file in scenes/ loads.
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using ssgi::loadScene;
using ssgi::Scene;

namespace {

const std::string kSourceDir = SSGI_SOURCE_DIR;
const std::string kModels = kSourceDir + "/scenes/models/";

size_t triangleCount(const Scene& scene) {
    size_t triangles = 0;
    for (const ssgi::Instance& instance : scene.instances)
        triangles += scene.meshes[size_t(instance.mesh)].indices.size() / 3;
    return triangles;
}

struct SceneModel {
    const char* file;
    size_t triangles;
};
void PrintTo(const SceneModel& scene, std::ostream* out) {
    *out << scene.file;
}

class SceneModels : public ::testing::TestWithParam<SceneModel> {};

TEST_P(SceneModels, LoadBareWithTheReadmeTriangleCount) {
    const std::string path = kModels + GetParam().file;
    if (!fs::exists(path)) GTEST_SKIP() << path << " is not there";
    const Scene scene = loadScene(path, {{"ground_plane", 0}}); // the model's triangles alone
    EXPECT_EQ(triangleCount(scene), GetParam().triangles);
    EXPECT_FALSE(scene.bounds.empty());
    EXPECT_LT(scene.light.outerConeAngle, glm::radians(89.0f));
    EXPECT_LT(scene.camera.znear, scene.camera.zfar);
    for (const ssgi::Mesh& mesh : scene.meshes) {
        EXPECT_LT(size_t(mesh.material), scene.materials.size());
        for (uint32_t index : mesh.indices)
            ASSERT_LT(index, mesh.vertices.size());
        for (const ssgi::Vertex& v : mesh.vertices)
            ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Readme, SceneModels,
    ::testing::Values(SceneModel{"cornell-box.glb", 36}, SceneModel{"cornell-box-sphere.glb", 2188},
                      SceneModel{"bunny.glb", 69451}, SceneModel{"mori-knob.glb", 11970},
                      SceneModel{"sponza.glb", 66450}, SceneModel{"sibenik.glb", 75283},
                      SceneModel{"conference.glb", 331179}, SceneModel{"scrub-pine.glb", 527}),
    [](const ::testing::TestParamInfo<SceneModel>& info) {
        std::string name = info.param.file;
        name = name.substr(0, name.find('.'));
        std::replace(name.begin(), name.end(), '-', '_');
        return name;
    });

TEST(SharedSceneDetails, CornellBoxWithoutNormalsIsFlatShaded) {
    const std::string path = kModels + "cornell-box.glb";
    if (!fs::exists(path)) GTEST_SKIP() << path << " is not there";
    const Scene scene = loadScene(path);
    for (const ssgi::Mesh& mesh : scene.meshes) {
        for (size_t t = 0; t < mesh.indices.size(); t += 3) {
            const ssgi::Vertex* v[3] = {&mesh.vertices[mesh.indices[t]],
                                        &mesh.vertices[mesh.indices[t + 1]],
                                        &mesh.vertices[mesh.indices[t + 2]]};
            const glm::vec3 cross =
                glm::cross(v[1]->position - v[0]->position, v[2]->position - v[0]->position);
            if (glm::length(cross) < 1e-12f) continue; // degenerate: any normal will do
            for (const ssgi::Vertex* corner : v)
                EXPECT_NEAR(glm::distance(corner->normal, glm::normalize(cross)), 0.0f, 1e-5f);
        }
    }
}

TEST(SharedSceneDetails, SponzaLoadsItsTextures) {
    const std::string path = kModels + "sponza.glb";
    if (!fs::exists(path)) GTEST_SKIP() << path << " is not there";
    const Scene scene = loadScene(path);
    ASSERT_EQ(scene.textures.size(), 18u);
    for (const ssgi::Texture& texture : scene.textures) {
        EXPECT_GT(texture.width, 0u);
        EXPECT_GT(texture.height, 0u);
        EXPECT_EQ(texture.rgba.size(), size_t(texture.width) * texture.height * 4);
    }
    const bool textured =
        std::any_of(scene.materials.begin(), scene.materials.end(),
                    [](const ssgi::Material& m) { return m.baseColorTexture >= 0; });
    EXPECT_TRUE(textured);
}

TEST(SceneFileSet, EverySceneFileLoads) {
    size_t count = 0;
    for (const auto& entry : fs::directory_iterator(kSourceDir + "/scenes")) {
        if (entry.path().extension() != ".json") continue;
        SCOPED_TRACE(entry.path().string());
        const std::string text =
            (std::ostringstream() << std::ifstream(entry.path()).rdbuf()).str();
        const Scene scene = loadScene(entry.path().string());
        EXPECT_FALSE(scene.instances.empty());
        for (size_t k = 1; k < scene.cameraPath.keys.size(); ++k)
            EXPECT_LE(scene.cameraPath.keys[k - 1].time, scene.cameraPath.keys[k].time);
        ++count;
    }
    EXPECT_GE(count, 1u);
}

} // namespace
