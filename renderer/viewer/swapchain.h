// The window's swapchain, the render pass the panel is drawn in (loading what the frame copied
// into the image), and the semaphores that order acquire, drawing and present.
#pragma once

#include "vk/context.h"

#include <vector>

namespace ssgi::viewer {

class Swapchain {
public:
    Swapchain(vk::Context& ctx, VkExtent2D size);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // After a resize (or an out-of-date present): waits for the device, rebuilds the images.
    void recreate(VkExtent2D size);

    // The next image to draw into, `acquired()` signalled when it may be written; false when
    // the swapchain no longer matches the window (recreate and try again).
    bool acquire(uint32_t& index);
    // Presents image `index` once `rendered(index)` is signalled; false when out of date.
    bool present(uint32_t index);

    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    uint32_t imageCount() const { return uint32_t(images_.size()); }
    uint32_t minImageCount() const { return minImageCount_; }
    VkImage image(uint32_t index) const { return images_[index]; }
    VkFramebuffer framebuffer(uint32_t index) const { return framebuffers_[index]; }
    VkRenderPass renderPass() const { return renderPass_; }
    VkSemaphore acquired() const { return acquired_; }
    VkSemaphore rendered(uint32_t index) const { return rendered_[index]; }
    // Whether the images can be copied from (screenshots).
    bool readable() const { return readable_; }

private:
    void create(VkExtent2D size);
    void destroyImages();

    vk::Context& ctx_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkColorSpaceKHR colorSpace_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    VkExtent2D extent_{};
    uint32_t minImageCount_ = 2;
    bool readable_ = false;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkFramebuffer> framebuffers_;
    VkSemaphore acquired_ = VK_NULL_HANDLE;
    std::vector<VkSemaphore> rendered_; // one per image: present may still wait on the last one
};

} // namespace ssgi::viewer
