#include "viewer/swapchain.h"

#include <algorithm>

namespace ssgi::viewer {

namespace {

// The frame is already encoded for display (the renderer's "ldr" image holds sRGB values), so a
// UNORM swapchain takes it as it is; ImGui's colours are meant for such a target too.
VkSurfaceFormatKHR chooseFormat(const vk::Context& ctx) {
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice, ctx.surface, &count, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice, ctx.surface, &count, formats.data());
    if (formats.empty()) throw vk::VulkanError("the window's surface offers no image format");
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
        for (const VkSurfaceFormatKHR& f : formats)
            if (f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
    return formats[0];
}

VkPresentModeKHR choosePresentMode(const vk::Context& ctx) {
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfacePresentModesKHR(ctx.physicalDevice, ctx.surface, &count, nullptr);
    std::vector<VkPresentModeKHR> modes(count);
    vkGetPhysicalDeviceSurfacePresentModesKHR(ctx.physicalDevice, ctx.surface, &count,
                                              modes.data());
    // Mailbox never waits for a vertical blank (the frame itself is the slow part); FIFO is the
    // one mode every device has.
    if (std::find(modes.begin(), modes.end(), VK_PRESENT_MODE_MAILBOX_KHR) != modes.end())
        return VK_PRESENT_MODE_MAILBOX_KHR;
    return VK_PRESENT_MODE_FIFO_KHR;
}

VkRenderPass createRenderPass(const vk::Context& ctx, VkFormat format) {
    // The frame was copied into the image by a transfer; the panel is drawn over it.
    VkAttachmentDescription color{};
    color.format = format;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkSubpassDependency deps[2]{};
    // The copies into the image before the panel is blended over them.
    deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    deps[0].dstSubpass = 0;
    deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    deps[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[0].dstAccessMask =
        VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    // A screenshot copies the image out after the panel.
    deps[1].srcSubpass = 0;
    deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &color;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = deps;
    VkRenderPass pass;
    VK_CHECK(vkCreateRenderPass(ctx.device, &info, nullptr, &pass));
    return pass;
}

VkSemaphore createSemaphore(const vk::Context& ctx) {
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore;
    VK_CHECK(vkCreateSemaphore(ctx.device, &info, nullptr, &semaphore));
    return semaphore;
}

} // namespace

Swapchain::Swapchain(vk::Context& ctx, VkExtent2D size) : ctx_(ctx) {
    const VkSurfaceFormatKHR surfaceFormat = chooseFormat(ctx);
    format_ = surfaceFormat.format;
    colorSpace_ = surfaceFormat.colorSpace;
    renderPass_ = createRenderPass(ctx, format_);
    create(size);
}

Swapchain::~Swapchain() {
    vkDeviceWaitIdle(ctx_.device);
    destroyImages();
    if (swapchain_) vkDestroySwapchainKHR(ctx_.device, swapchain_, nullptr);
    vkDestroyRenderPass(ctx_.device, renderPass_, nullptr);
}

void Swapchain::destroyImages() {
    for (VkFramebuffer f : framebuffers_)
        vkDestroyFramebuffer(ctx_.device, f, nullptr);
    for (VkImageView v : views_)
        vkDestroyImageView(ctx_.device, v, nullptr);
    for (VkSemaphore s : rendered_)
        vkDestroySemaphore(ctx_.device, s, nullptr);
    if (acquired_) vkDestroySemaphore(ctx_.device, acquired_, nullptr);
    framebuffers_.clear();
    views_.clear();
    rendered_.clear();
    images_.clear();
    acquired_ = VK_NULL_HANDLE;
}

void Swapchain::recreate(VkExtent2D size) {
    vkDeviceWaitIdle(ctx_.device);
    destroyImages();
    create(size);
}

void Swapchain::create(VkExtent2D size) {
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx_.physicalDevice, ctx_.surface, &caps));
    // The surface's own extent wins where it has one; else the window's, within its limits.
    extent_ = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent : size;
    extent_.width = std::clamp(extent_.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent_.height =
        std::clamp(extent_.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    const VkImageUsageFlags needed =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if ((caps.supportedUsageFlags & needed) != needed)
        throw vk::VulkanError("the window's swapchain images cannot be copied into");
    readable_ = caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    minImageCount_ = std::max(2u, caps.minImageCount);
    uint32_t imageCount = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);

    VkSwapchainKHR old = swapchain_;
    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = ctx_.surface;
    info.minImageCount = imageCount;
    info.imageFormat = format_;
    info.imageColorSpace = colorSpace_;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = needed | (readable_ ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = choosePresentMode(ctx_);
    info.clipped = VK_TRUE;
    info.oldSwapchain = old;
    VK_CHECK(vkCreateSwapchainKHR(ctx_.device, &info, nullptr, &swapchain_));
    if (old) vkDestroySwapchainKHR(ctx_.device, old, nullptr);

    uint32_t count = 0;
    vkGetSwapchainImagesKHR(ctx_.device, swapchain_, &count, nullptr);
    images_.resize(count);
    vkGetSwapchainImagesKHR(ctx_.device, swapchain_, &count, images_.data());
    for (VkImage image : images_) {
        VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        viewInfo.image = image;
        viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = format_;
        viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view;
        VK_CHECK(vkCreateImageView(ctx_.device, &viewInfo, nullptr, &view));
        views_.push_back(view);
        VkFramebufferCreateInfo fbInfo{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fbInfo.renderPass = renderPass_;
        fbInfo.attachmentCount = 1;
        fbInfo.pAttachments = &view;
        fbInfo.width = extent_.width;
        fbInfo.height = extent_.height;
        fbInfo.layers = 1;
        VkFramebuffer framebuffer;
        VK_CHECK(vkCreateFramebuffer(ctx_.device, &fbInfo, nullptr, &framebuffer));
        framebuffers_.push_back(framebuffer);
        rendered_.push_back(createSemaphore(ctx_));
    }
    acquired_ = createSemaphore(ctx_);
}

bool Swapchain::acquire(uint32_t& index) {
    VkResult result = vkAcquireNextImageKHR(ctx_.device, swapchain_, UINT64_MAX, acquired_,
                                            VK_NULL_HANDLE, &index);
    if (result == VK_ERROR_OUT_OF_DATE_KHR) return false;
    if (result != VK_SUBOPTIMAL_KHR) VK_CHECK(result);
    return true;
}

bool Swapchain::present(uint32_t index) {
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &rendered_[index];
    info.swapchainCount = 1;
    info.pSwapchains = &swapchain_;
    info.pImageIndices = &index;
    VkResult result = vkQueuePresentKHR(ctx_.queue, &info);
    if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) return false;
    VK_CHECK(result);
    return true;
}

} // namespace ssgi::viewer
