#include "vk/texel_decode.h"

#include "vk/context.h"

#include <glm/gtc/packing.hpp>

#include <cstring>

namespace ssgi::vk {

std::vector<float> decodeTexels(VkFormat format, const uint8_t* bytes, size_t count,
                                const std::string& image) {
    std::vector<float> rgba(count * 4, 0.0f);
    for (size_t i = 0; i < count; ++i) {
        float* out = &rgba[4 * i];
        switch (format) {
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            std::memcpy(out, bytes + 16 * i, 16);
            break;
        case VK_FORMAT_R16G16B16A16_SFLOAT: {
            uint16_t h[4];
            std::memcpy(h, bytes + 8 * i, 8);
            for (int c = 0; c < 4; ++c)
                out[c] = glm::unpackHalf1x16(h[c]);
            break;
        }
        case VK_FORMAT_R16G16_SFLOAT:
        case VK_FORMAT_R16_SFLOAT: {
            const int channels = format == VK_FORMAT_R16_SFLOAT ? 1 : 2;
            uint16_t h[2];
            std::memcpy(h, bytes + 2 * channels * i, 2 * channels);
            for (int c = 0; c < channels; ++c)
                out[c] = glm::unpackHalf1x16(h[c]);
            out[3] = 1.0f;
            break;
        }
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_R8G8B8A8_SRGB:
            for (int c = 0; c < 4; ++c)
                out[c] = bytes[4 * i + c] / 255.0f;
            break;
        case VK_FORMAT_R8_UNORM:
            out[0] = bytes[i] / 255.0f;
            out[3] = 1.0f;
            break;
        case VK_FORMAT_D16_UNORM: {
            uint16_t d = 0;
            std::memcpy(&d, bytes + 2 * i, 2);
            out[0] = float(d) / 65535.0f;
            out[3] = 1.0f;
            break;
        }
        case VK_FORMAT_D32_SFLOAT:
        case VK_FORMAT_R32_SFLOAT:
            std::memcpy(out, bytes + 4 * i, 4);
            out[3] = 1.0f;
            break;
        case VK_FORMAT_R8_UINT: // small whole numbers (distances): their values
            out[0] = float(bytes[i]);
            out[3] = 1.0f;
            break;
        case VK_FORMAT_R32_UINT: // keys, bit masks and counts: their bits, as the header says
            std::memcpy(out, bytes + 4 * i, 4);
            out[3] = 1.0f;
            break;
        default:
            throw VulkanError("download: unsupported format for " + image);
        }
    }
    return rgba;
}

} // namespace ssgi::vk
