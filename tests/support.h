// Shared by the tests: a Vulkan context with the validation layer and synchronization
// validation on, and a fixture that fails any test during which the layer said anything.
#pragma once

#include "scene/scene.h"
#include "vk/context.h"

#include <glm/glm.hpp>

#include <gtest/gtest.h>

#include <string>

namespace ssgi::test {

// One context per test process (creating instances is slow on lavapipe under validation).
vk::Context& context();

std::string sourcePath(const std::string& relative); // a path inside the repository
std::string sceneModel(const std::string& name);     // scenes/models/NAME

// One frame of a scene with the real-time renderer, and the images a test reads from it.
struct Frame {
    uint32_t width = 0, height = 0;
    std::vector<float> direct, position, normal, albedo, hdr, ldr, ao, indirect, ssdo, shadow;
    size_t pixels() const { return size_t(width) * height; }
    static float luminance(const std::vector<float>& rgba, size_t pixel) {
        return 0.2126f * rgba[4 * pixel] + 0.7152f * rgba[4 * pixel + 1] +
               0.0722f * rgba[4 * pixel + 2];
    }
    static glm::vec3 at(const std::vector<float>& rgba, size_t pixel) {
        return {rgba[4 * pixel], rgba[4 * pixel + 1], rgba[4 * pixel + 2]};
    }
    bool geometry(size_t pixel) const { return position[4 * pixel + 3] != 0.0f; }
};
// Renders `frames` frames from the scene's camera and reads back every image the frame made
// (an effect that is off leaves its vector empty).
Frame render(const Scene& scene, uint32_t width, uint32_t height, uint32_t frames = 1);

// The scene made k times larger, its light k^2 times stronger: every radiance stays the same.
Scene scaledScene(Scene scene, float k);
// The scales the scene-unit tests render at: 1e-9 to 1e9 units.
inline constexpr float kSceneScales[] = {1e-9f, 1e-6f, 1e-3f, 1e3f, 1e6f, 1e9f};

// Whether the segment from `origin` to `target` crosses any triangle of the scene (exact, on the
// CPU): the independent geometry the image tests compare against.
bool segmentBlocked(const Scene& scene, glm::vec3 origin, glm::vec3 target);

// A command line run through the shell, its stdout and stderr together, and its exit status
// (-1 when it did not exit normally or could not be started).
struct CommandResult {
    int status = -1;
    std::string output;
};
CommandResult runCommand(const std::string& command);

class VulkanTest : public ::testing::Test {
protected:
    void SetUp() override { messagesBefore_ = context().validationMessageCount(); }
    void TearDown() override {
        EXPECT_EQ(context().validationMessageCount(), messagesBefore_)
            << "the validation layer reported messages during this test (see stderr)";
    }

private:
    uint32_t messagesBefore_ = 0;
};

} // namespace ssgi::test
