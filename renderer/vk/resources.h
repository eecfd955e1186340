// Buffers and images with their own memory (one allocation each: our scenes need a few dozen
// resources, so a sub-allocator would be code without benefit), upload and readback.
#pragma once

#include "vk/context.h"

#include <string>
#include <vector>

namespace ssgi::vk {

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr; // host-visible buffers stay mapped
};

struct Image {
    std::string name;
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    VkDeviceSize memorySize = 0; // bytes of device memory it holds
};

uint32_t findMemoryType(const Context& ctx, uint32_t typeBits, VkMemoryPropertyFlags flags);

Buffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                    bool hostVisible);
void destroyBuffer(const Context& ctx, Buffer& buffer);

// Device-local buffer filled from host memory through a staging buffer.
Buffer createBufferWithData(Context& ctx, const void* data, VkDeviceSize size,
                            VkBufferUsageFlags usage);

Image createImage(const Context& ctx, const std::string& name, VkFormat format, VkExtent2D extent,
                  VkImageUsageFlags usage);
void destroyImage(const Context& ctx, Image& image);

// Records one layout transition of a single-level, single-layer image with its dependency.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                  VkImageLayout to, VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStages, VkAccessFlags2 dstAccess);

// Sampled texture (SHADER_READ_ONLY_OPTIMAL afterwards) from tightly packed pixels.
Image createTexture(Context& ctx, const std::string& name, VkFormat format, VkExtent2D extent,
                    const void* pixels, VkDeviceSize size);

bool isDepthFormat(VkFormat format);
uint32_t formatTexelSize(VkFormat format);

} // namespace ssgi::vk
