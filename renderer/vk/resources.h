// Buffers and images with their own memory (one allocation each: our scenes need a few dozen
// resources, so a sub-allocator would be code without benefit), upload and readback. The one
// exception is the frame graph's transient images, which it binds into one block of its own
// where their lifetimes within a frame do not overlap (createUnboundImage, bindImage).
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
    VkImageUsageFlags usage = 0;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    VkDeviceSize memorySize = 0; // bytes of device memory it needs
    VkMemoryRequirements requirements{};
    bool ownsMemory = true; // false: bound into memory someone else allocated (bindImage)
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
// The same image without memory (nor a view) yet: its `requirements` say what it needs.
Image createUnboundImage(const Context& ctx, const std::string& name, VkFormat format,
                         VkExtent2D extent, VkImageUsageFlags usage);
// Binds an unbound image at `offset` of `memory`, which the caller owns and frees, and makes its
// view.
void bindImage(const Context& ctx, Image& image, VkDeviceMemory memory, VkDeviceSize offset);
// Device-local memory of `size` bytes of a type in `typeBits`.
VkDeviceMemory allocateDeviceMemory(const Context& ctx, VkDeviceSize size, uint32_t typeBits);
void destroyImage(const Context& ctx, Image& image);

// Records one layout transition of a single-level, single-layer image with its dependency.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                  VkImageLayout to, VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStages, VkAccessFlags2 dstAccess);
// Records the clearing of a colour image, in TRANSFER_DST_OPTIMAL, to zero (every channel).
void clearToZero(VkCommandBuffer cmd, VkImage image);
// Every channel of a colour image (in TRANSFER_DST_OPTIMAL) set to `value`.
void clearTo(VkCommandBuffer cmd, VkImage image, float value);
// Records the dependency of later accesses to a whole buffer on earlier ones.
void bufferBarrier(VkCommandBuffer cmd, VkBuffer buffer, VkPipelineStageFlags2 srcStages,
                   VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStages,
                   VkAccessFlags2 dstAccess);

// Sampled texture (SHADER_READ_ONLY_OPTIMAL afterwards) from tightly packed pixels.
Image createTexture(Context& ctx, const std::string& name, VkFormat format, VkExtent2D extent,
                    const void* pixels, VkDeviceSize size);

bool isDepthFormat(VkFormat format);
uint32_t formatTexelSize(VkFormat format);

} // namespace ssgi::vk
