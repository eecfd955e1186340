#include "viewer/presenter.h"

#include <algorithm>
#include <cstring>

namespace ssgi::viewer {

namespace {

// Every image the presenter moves is a single-level colour image.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStages, VkAccessFlags2 dstAccess) {
    vk::imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, from, to, srcStages, srcAccess,
                     dstStages, dstAccess);
}

constexpr VkPipelineStageFlags2 kTransfer = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
constexpr VkPipelineStageFlags2 kAcquireStages =
    VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;

} // namespace

Presenter::Presenter(vk::Context& ctx, Swapchain& swapchain, Gui& gui)
    : ctx_(ctx), swapchain_(swapchain), gui_(gui) {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = ctx.commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(ctx.device, &alloc, &cmd_));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(ctx.device, &fenceInfo, nullptr, &fence_));
}

Presenter::~Presenter() {
    vkDeviceWaitIdle(ctx_.device);
    if (cpuImage_.image) vk::destroyImage(ctx_, cpuImage_);
    if (cpuStaging_.buffer) vk::destroyBuffer(ctx_, cpuStaging_);
    if (readback_.buffer) vk::destroyBuffer(ctx_, readback_);
    vkDestroyFence(ctx_.device, fence_, nullptr);
    vkFreeCommandBuffers(ctx_.device, ctx_.commandPool, 1, &cmd_);
}

void Presenter::uploadPixels(VkCommandBuffer cmd, const std::vector<uint8_t>& pixels,
                             VkExtent2D size) {
    const VkDeviceSize bytes = VkDeviceSize(size.width) * size.height * 4;
    if (pixels.size() != bytes) throw vk::VulkanError("viewer: CPU view of the wrong size");
    if (cpuImage_.extent.width != size.width || cpuImage_.extent.height != size.height) {
        if (cpuImage_.image) vk::destroyImage(ctx_, cpuImage_);
        if (cpuStaging_.buffer) vk::destroyBuffer(ctx_, cpuStaging_);
        cpuImage_ =
            vk::createImage(ctx_, "viewer.cpu-view", VK_FORMAT_R8G8B8A8_UNORM, size,
                            VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        cpuStaging_ = vk::createBuffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    }
    // The last frame's copy out of this buffer and image has completed (one frame in flight).
    std::memcpy(cpuStaging_.mapped, pixels.data(), bytes);
    imageBarrier(cmd, cpuImage_.image, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kTransfer, 0, kTransfer,
                 VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {size.width, size.height, 1};
    vkCmdCopyBufferToImage(cmd, cpuStaging_.buffer, cpuImage_.image,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    imageBarrier(cmd, cpuImage_.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 kTransfer, VK_ACCESS_2_TRANSFER_READ_BIT);
}

void Presenter::readBack(VkCommandBuffer cmd, VkImage image, VkExtent2D extent) {
    const VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
    if (readback_.size < bytes) {
        if (readback_.buffer) vk::destroyBuffer(ctx_, readback_);
        readback_ = vk::createBuffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    }
    // The render pass left the image for presenting, after a dependency on its transfer reads.
    imageBarrier(cmd, image, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 kTransfer, 0, kTransfer, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer, 1,
                           &region);
    imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                 kTransfer, 0, VK_PIPELINE_STAGE_2_NONE, 0);
}

bool Presenter::draw(const FrameSource& source, VkRect2D sceneRect,
                     std::vector<float>* screenshot) {
    uint32_t index = 0;
    if (!swapchain_.acquire(index)) {
        gui_.cancelFrame();
        return false;
    }
    const VkImage target = swapchain_.image(index);
    const VkExtent2D extent = swapchain_.extent();
    VK_CHECK(vkResetCommandBuffer(cmd_, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));

    // The acquired image's old contents do not matter: clear it, then copy the scene in.
    imageBarrier(cmd_, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 kAcquireStages, 0, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkClearColorValue background{{0.08f, 0.08f, 0.09f, 1.0f}};
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd_, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &background, 1, &all);
    imageBarrier(cmd_, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT);

    const vk::Image* from = nullptr;
    if (source.pixels && source.renderer) {
        uploadPixels(cmd_, *source.pixels, source.renderer->size());
        from = &cpuImage_;
    } else if (source.renderer) {
        from = &source.renderer->prepareCopySource(cmd_, "ldr");
    }
    if (from && sceneRect.extent.width > 0 && sceneRect.extent.height > 0) {
        VkImageBlit blit{};
        blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.srcOffsets[1] = {int32_t(from->extent.width), int32_t(from->extent.height), 1};
        blit.dstSubresource = blit.srcSubresource;
        blit.dstOffsets[0] = {sceneRect.offset.x, sceneRect.offset.y, 0};
        blit.dstOffsets[1] = {
            std::min(sceneRect.offset.x + int32_t(sceneRect.extent.width), int32_t(extent.width)),
            std::min(sceneRect.offset.y + int32_t(sceneRect.extent.height), int32_t(extent.height)),
            1};
        const bool sameSize = from->extent.width == sceneRect.extent.width &&
                              from->extent.height == sceneRect.extent.height;
        vkCmdBlitImage(cmd_, from->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                       sameSize ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
    }

    // The panel over it (the render pass waits for the copies and leaves the image presentable).
    VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    pass.renderPass = swapchain_.renderPass();
    pass.framebuffer = swapchain_.framebuffer(index);
    pass.renderArea = {{0, 0}, extent};
    vkCmdBeginRenderPass(cmd_, &pass, VK_SUBPASS_CONTENTS_INLINE);
    gui_.record(cmd_);
    vkCmdEndRenderPass(cmd_);
    const bool readBackNow = screenshot && swapchain_.readable();
    if (readBackNow) readBack(cmd_, target, extent);
    VK_CHECK(vkEndCommandBuffer(cmd_));

    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = swapchain_.acquired();
    wait.stageMask = kAcquireStages;
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal.semaphore = swapchain_.rendered(index);
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = cmd_;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.waitSemaphoreInfoCount = 1;
    submit.pWaitSemaphoreInfos = &wait;
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    submit.signalSemaphoreInfoCount = 1;
    submit.pSignalSemaphoreInfos = &signal;
    VK_CHECK(vkQueueSubmit2(ctx_.queue, 1, &submit, fence_));
    const bool presented = swapchain_.present(index);
    // One frame in flight: the renderer's next frame reuses what this one read.
    VK_CHECK(vkWaitForFences(ctx_.device, 1, &fence_, VK_TRUE, UINT64_MAX));
    VK_CHECK(vkResetFences(ctx_.device, 1, &fence_));

    if (readBackNow) {
        const size_t count = size_t(extent.width) * extent.height;
        screenshot->assign(count * 4, 1.0f);
        const auto* bytes = static_cast<const uint8_t*>(readback_.mapped);
        const bool bgra = swapchain_.format() == VK_FORMAT_B8G8R8A8_UNORM ||
                          swapchain_.format() == VK_FORMAT_B8G8R8A8_SRGB;
        for (size_t i = 0; i < count; ++i)
            for (int c = 0; c < 3; ++c)
                (*screenshot)[4 * i + c] = bytes[4 * i + (bgra ? 2 - c : c)] / 255.0f;
    } else if (screenshot) {
        screenshot->clear();
    }
    return presented;
}

} // namespace ssgi::viewer
