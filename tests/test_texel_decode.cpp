// Reading an image back: its texels, in their own format, become RGBA floats (vk/texel_decode.h),
// the layout the host's readers take; checked here texel by texel, without a device.
#include "vk/context.h"
#include "vk/texel_decode.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <cstring>

using namespace ssgi;

namespace {

template <typename T> std::vector<uint8_t> bytesOf(const std::vector<T>& values) {
    std::vector<uint8_t> bytes(values.size() * sizeof(T));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

TEST(TexelDecode, HalfFloatsUnpackWithTheMissingChannelsZeroAndAlphaOne) {
    // Two RG16F texels: a cache's count and whether it is due.
    const std::vector<uint16_t> rg = {glm::packHalf1x16(36.0f), glm::packHalf1x16(1.0f),
                                      glm::packHalf1x16(0.5f), glm::packHalf1x16(0.0f)};
    const std::vector<uint8_t> bytes = bytesOf(rg);
    const std::vector<float> out = vk::decodeTexels(VK_FORMAT_R16G16_SFLOAT, bytes.data(), 2, "c");
    EXPECT_EQ(out, (std::vector<float>{36.0f, 1.0f, 0.0f, 1.0f, 0.5f, 0.0f, 0.0f, 1.0f}));
    const std::vector<float> r = vk::decodeTexels(VK_FORMAT_R16_SFLOAT, bytes.data(), 2, "r");
    EXPECT_EQ(r, (std::vector<float>{36.0f, 0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 0.0f, 1.0f}));
}

TEST(TexelDecode, FullFloatsEightBitChannelsAndDepth) {
    const std::vector<float> rgba = {1.5f, -2.0f, 0.25f, 7.0f};
    const std::vector<uint8_t> f32 = bytesOf(rgba);
    EXPECT_EQ(vk::decodeTexels(VK_FORMAT_R32G32B32A32_SFLOAT, f32.data(), 1, "f"), rgba);
    const std::vector<uint8_t> unorm = {0, 51, 255, 102};
    EXPECT_EQ(vk::decodeTexels(VK_FORMAT_R8G8B8A8_UNORM, unorm.data(), 1, "u"),
              (std::vector<float>{0.0f, 0.2f, 1.0f, 0.4f}));
    const std::vector<uint16_t> depth = {65535};
    const std::vector<uint8_t> d16 = bytesOf(depth);
    EXPECT_EQ(vk::decodeTexels(VK_FORMAT_D16_UNORM, d16.data(), 1, "d"),
              (std::vector<float>{1.0f, 0.0f, 0.0f, 1.0f}));
}

TEST(TexelDecode, AFormatItDoesNotDecodeIsAnErrorNamingTheImage) {
    const std::vector<uint8_t> bytes(16, 0);
    try {
        vk::decodeTexels(VK_FORMAT_R32G32B32A32_UINT, bytes.data(), 1, "rsm.vpls");
        ADD_FAILURE() << "decoded";
    } catch (const vk::VulkanError& e) {
        EXPECT_NE(std::string(e.what()).find("rsm.vpls"), std::string::npos) << e.what();
    }
}

} // namespace
