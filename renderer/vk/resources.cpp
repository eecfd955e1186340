#include "vk/resources.h"

#include <cstring>

namespace ssgi::vk {

uint32_t findMemoryType(const Context& ctx, uint32_t typeBits, VkMemoryPropertyFlags flags) {
    const VkPhysicalDeviceMemoryProperties& mem = ctx.memoryProperties;
    for (uint32_t i = 0; i < mem.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw VulkanError("no Vulkan memory type with the needed properties");
}

static VkDeviceMemory allocate(const Context& ctx, VkMemoryRequirements req,
                               VkMemoryPropertyFlags flags) {
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = req.size;
    info.memoryTypeIndex = findMemoryType(ctx, req.memoryTypeBits, flags);
    VkDeviceMemory memory;
    VK_CHECK(vkAllocateMemory(ctx.device, &info, nullptr, &memory));
    return memory;
}

Buffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                    bool hostVisible) {
    Buffer b;
    b.size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    VK_CHECK(vkCreateBuffer(ctx.device, &info, nullptr, &b.buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx.device, b.buffer, &req);
    VkMemoryPropertyFlags flags =
        hostVisible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                    : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    b.memory = allocate(ctx, req, flags);
    VK_CHECK(vkBindBufferMemory(ctx.device, b.buffer, b.memory, 0));
    if (hostVisible) VK_CHECK(vkMapMemory(ctx.device, b.memory, 0, size, 0, &b.mapped));
    return b;
}

void destroyBuffer(const Context& ctx, Buffer& b) {
    if (b.buffer) vkDestroyBuffer(ctx.device, b.buffer, nullptr);
    if (b.memory) vkFreeMemory(ctx.device, b.memory, nullptr);
    b = {};
}

Buffer createBufferWithData(Context& ctx, const void* data, VkDeviceSize size,
                            VkBufferUsageFlags usage) {
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, data, size);
    Buffer b = createBuffer(ctx, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, size};
        vkCmdCopyBuffer(cmd, staging.buffer, b.buffer, 1, &region);
    });
    destroyBuffer(ctx, staging);
    return b;
}

bool isDepthFormat(VkFormat format) {
    return format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM ||
           format == VK_FORMAT_D24_UNORM_S8_UINT || format == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

uint32_t formatTexelSize(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R16G16_SFLOAT:
        return 4;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_D16_UNORM:
        return 2;
    case VK_FORMAT_R8_UINT:
    case VK_FORMAT_R8_UNORM:
        return 1;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_UINT:
        return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_UINT:
        return 16;
    default:
        throw VulkanError("formatTexelSize: format not used by this renderer");
    }
}

Image createUnboundImage(const Context& ctx, const std::string& name, VkFormat format,
                         VkExtent2D extent, VkImageUsageFlags usage) {
    Image img;
    img.name = name;
    img.format = format;
    img.extent = extent;
    img.usage = usage;
    img.aspect = isDepthFormat(format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {extent.width, extent.height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VK_CHECK(vkCreateImage(ctx.device, &info, nullptr, &img.image));
    vkGetImageMemoryRequirements(ctx.device, img.image, &img.requirements);
    img.memorySize = img.requirements.size;
    ctx.nameObject(VK_OBJECT_TYPE_IMAGE, uint64_t(img.image), name);
    return img;
}

VkDeviceMemory allocateDeviceMemory(const Context& ctx, VkDeviceSize size, uint32_t typeBits) {
    VkMemoryRequirements req{};
    req.size = size;
    req.memoryTypeBits = typeBits;
    return allocate(ctx, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
}

void bindImage(const Context& ctx, Image& img, VkDeviceMemory memory, VkDeviceSize offset) {
    VK_CHECK(vkBindImageMemory(ctx.device, img.image, memory, offset));
    img.memory = memory;
    // Images used only for copies and clears have no view.
    const VkImageUsageFlags viewUsage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    if (!(img.usage & viewUsage)) return;
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = img.image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = img.format;
    viewInfo.subresourceRange = {img.aspect, 0, 1, 0, 1};
    VK_CHECK(vkCreateImageView(ctx.device, &viewInfo, nullptr, &img.view));
}

Image createImage(const Context& ctx, const std::string& name, VkFormat format, VkExtent2D extent,
                  VkImageUsageFlags usage) {
    Image img = createUnboundImage(ctx, name, format, extent, usage);
    bindImage(ctx, img, allocate(ctx, img.requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT), 0);
    return img;
}

void destroyImage(const Context& ctx, Image& img) {
    if (img.view) vkDestroyImageView(ctx.device, img.view, nullptr);
    if (img.image) vkDestroyImage(ctx.device, img.image, nullptr);
    if (img.memory && img.ownsMemory) vkFreeMemory(ctx.device, img.memory, nullptr);
    img = {};
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                  VkImageLayout to, VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStages, VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStages;
    b.srcAccessMask = srcAccess;
    b.dstStageMask = dstStages;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void clearToZero(VkCommandBuffer cmd, VkImage image) {
    clearTo(cmd, image, 0.0f);
}

void clearTo(VkCommandBuffer cmd, VkImage image, float value) {
    const VkClearColorValue colour{{value, value, value, value}};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &colour, 1, &range);
}

void bufferBarrier(VkCommandBuffer cmd, VkBuffer buffer, VkPipelineStageFlags2 srcStages,
                   VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStages,
                   VkAccessFlags2 dstAccess) {
    VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    b.srcStageMask = srcStages;
    b.srcAccessMask = srcAccess;
    b.dstStageMask = dstStages;
    b.dstAccessMask = dstAccess;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer;
    b.size = VK_WHOLE_SIZE;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.bufferMemoryBarrierCount = 1;
    dep.pBufferMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

Image createTexture(Context& ctx, const std::string& name, VkFormat format, VkExtent2D extent,
                    const void* pixels, VkDeviceSize size) {
    Image img = createImage(ctx, name, format, extent,
                            VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, pixels, size);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        imageBarrier(cmd, img.image, img.aspect, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);

        VkBufferImageCopy region{};
        region.imageSubresource = {img.aspect, 0, 0, 1};
        region.imageExtent = {extent.width, extent.height, 1};
        vkCmdCopyBufferToImage(cmd, staging.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               1, &region);

        imageBarrier(cmd, img.image, img.aspect, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    });
    destroyBuffer(ctx, staging);
    return img;
}

} // namespace ssgi::vk
