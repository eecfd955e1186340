// The texels of an image as they were read back (its own format, tightly packed) turned into
// RGBA floats, the one layout every reader on the host takes: half floats unpacked, 8-bit
// channels over 255, depth in R; channels the format lacks read 0, and alpha 1.
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
