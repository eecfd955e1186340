// Shared by the tests: a Vulkan context with the validation layer and synchronization
// validation on, and a fixture that fails any test during which the layer said anything.
#pragma once

#include "vk/context.h"

#include <gtest/gtest.h>

#include <string>

namespace ssgi::test {

// One context per test process (creating instances is slow on lavapipe under validation).
vk::Context& context();

std::string sourcePath(const std::string& relative); // a path inside the repository
std::string sharedScene(const std::string& name);    // ../shared/scenes/NAME

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
