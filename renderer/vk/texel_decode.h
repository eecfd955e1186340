// The texels of an image as they were read back (its own format, tightly packed) turned into
// RGBA floats, the one layout every reader on the host takes: half floats unpacked, 8-bit
// channels over 255, depth in R; channels the format lacks read 0, and alpha 1. An R8UI texel
// (a small whole number) is its value in R. An R32UI texel
// (a key, a bit mask, a count) keeps its 32 bits in R's float, which readers take back with
// std::bit_cast<uint32_t> (a float cannot hold every such number as a value).
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ssgi::vk {

// `count` texels of `format` from `bytes`; throws VulkanError naming `image` for a format it
// does not decode.
std::vector<float> decodeTexels(VkFormat format, const uint8_t* bytes, size_t count,
                                const std::string& image);

} // namespace ssgi::vk
