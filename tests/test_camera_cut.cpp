// Camera cuts: a cut restarts every cached history, asked for (Renderer::cut(), a
// camera path key with "cut": true) or by itself when the camera turns or jumps beyond the
// cache_cut_* settings between two frames; an ordinary step of a camera path is no cut.
#include "renderer.h"
#include "scene/camera.h"
#include "support.h"

#include <glm/gtc/quaternion.hpp>

#include <fstream>

using namespace ssgi;

namespace {

class CameraCutTest : public test::VulkanTest {
protected:
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    // Pixels of the AO history that continued from the last frame (count > 1 in its meta).
    static double continued(Renderer& r) {
        const std::vector<float> meta = r.readImage("ao.meta");
        const std::vector<float> position = r.readImage("gbuffer.position");
        size_t kept = 0, geometry = 0;
        for (size_t i = 0; i < meta.size(); i += 4) {
            if (position[i + 3] == 0.0f) continue;
            ++geometry;
            kept += meta[i + 3] > 1.0f;
        }
        return geometry ? double(kept) / double(geometry) : 0.0;
    }
};

TEST_F(CameraCutTest, AnExplicitCutRestartsEveryHistory) {
    Renderer r(test::context(), scene, {32, 32});
    for (int i = 0; i < 3; ++i)
        r.renderFrame(scene.camera);
    EXPECT_GT(continued(r), 0.9);
    r.cut();
    r.renderFrame(scene.camera);
    EXPECT_EQ(r.cuts(), 1u);
    EXPECT_EQ(continued(r), 0.0) << "no history survives a cut, not even under a still camera";
    r.renderFrame(scene.camera);
    EXPECT_GT(continued(r), 0.9) << "and the next frame accumulates again";
}

// The same once the still camera has settled (the effects then compute nothing, and each
// history is carried over as it is): a cut ends that state too.
TEST_F(CameraCutTest, ACutAfterTheScreenSettledRestartsEveryHistory) {
    Renderer r(test::context(), scene, {32, 32});
    for (int i = 0; i < 40; ++i) // cache_rotations (36) still frames and a few more
        r.renderFrame(scene.camera);
    EXPECT_GT(continued(r), 0.9);
    r.cut();
    r.renderFrame(scene.camera);
    EXPECT_EQ(continued(r), 0.0) << "a settled screen keeps no history past a cut either";
}

TEST_F(CameraCutTest, ALargeTurnOrJumpIsACutAndASmallStepIsNot) {
    Renderer r(test::context(), scene, {32, 32});
    Camera camera = scene.camera;
    r.renderFrame(camera);
    // A small step: 1% of the diagonal, 2 degrees.
    camera.position += 0.01f * glm::length(scene.bounds.size()) * glm::vec3(1, 0, 0);
    camera.orientation =
        glm::angleAxis(glm::radians(2.0f), glm::vec3(0, 1, 0)) * camera.orientation;
    r.renderFrame(camera);
    EXPECT_EQ(r.cuts(), 0u);
    // A turn of 60 degrees (beyond cache_cut_angle_deg, 45).
    camera.orientation =
        glm::angleAxis(glm::radians(60.0f), glm::vec3(0, 1, 0)) * camera.orientation;
    r.renderFrame(camera);
    EXPECT_EQ(r.cuts(), 1u);
    // A jump of half the diagonal (beyond cache_cut_distance, 0.2).
    camera.position += 0.5f * glm::length(scene.bounds.size()) * glm::vec3(0, 0, 1);
    r.renderFrame(camera);
    EXPECT_EQ(r.cuts(), 2u);
    // Turned off: 180 degrees and a huge distance never cut.
    Scene never = scene;
    never.settings.cache_cut_angle_deg = 180;
    never.settings.cache_cut_distance = 1e9;
    Renderer n(test::context(), never, {32, 32});
    n.renderFrame(scene.camera);
    n.renderFrame(camera);
    EXPECT_EQ(n.cuts(), 0u);
}

TEST_F(CameraCutTest, APathKeyMarkedCutRestartsWhenSetTimeCrossesIt) {
    const std::string path = testing::TempDir() + "ssgi-cut-path.json";
    std::ofstream(path) << R"({
      "materials": { "white": { "albedo": [0.8, 0.8, 0.8] } },
      "objects": [ { "type": "box", "material": "white", "center": [0, 0.5, 0], "size": [1, 1, 1] } ],
      "camera": { "position": [0, 1, 4], "target": [0, 0.5, 0] },
      "camera_path": [
        { "time": 0, "position": [0, 1, 4], "target": [0, 0.5, 0] },
        { "time": 1, "position": [0.05, 1, 4], "target": [0, 0.5, 0] },
        { "time": 1, "position": [0.1, 1, 4], "target": [0, 0.5, 0], "cut": true },
        { "time": 2, "position": [0.15, 1, 4], "target": [0, 0.5, 0] }
      ]
    })";
    const Scene s = loadScene(path);
    ASSERT_EQ(s.cameraPath.keys.size(), 4u);
    EXPECT_FALSE(s.cameraPath.keys[1].cut);
    EXPECT_TRUE(s.cameraPath.keys[2].cut);
    Renderer r(test::context(), s, {32, 32});
    for (float t : {0.0f, 0.5f, 0.9f}) {
        r.setTime(t);
        r.renderFrame(cameraAt(s.cameraPath, t));
    }
    EXPECT_EQ(r.cuts(), 0u) << "small steps before the key";
    r.setTime(1.2f);
    r.renderFrame(cameraAt(s.cameraPath, 1.2f));
    EXPECT_EQ(r.cuts(), 1u);
    r.setTime(1.5f);
    r.renderFrame(cameraAt(s.cameraPath, 1.5f));
    EXPECT_EQ(r.cuts(), 1u) << "once";
    // A cut that is not a boolean is bad input naming the key.
    std::ofstream(path) << R"({ "materials": { "white": { "albedo": [0.8, 0.8, 0.8] } },
      "objects": [ { "type": "box", "material": "white", "center": [0, 0, 0], "size": [1, 1, 1] } ],
      "camera_path": [ { "time": 0, "position": [0, 1, 4], "target": [0, 0, 0], "cut": 1 } ] })";
    try {
        loadScene(path);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("camera_path[0].cut"), std::string::npos) << e.what();
    }
}

} // namespace
