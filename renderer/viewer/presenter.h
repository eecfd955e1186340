// One window frame: the renderer's output (or a view made on the CPU) copied into the scene's
// rectangle of a swapchain image, the panel drawn over it, presented; optionally read back.
#pragma once

#include "renderer.h"
#include "viewer/gui.h"
#include "viewer/swapchain.h"

#include <cstdint>
#include <vector>

namespace ssgi::viewer {

// What fills the scene's rectangle this frame: the renderer's "ldr" image (the final image or
// one of the composite's views), or RGBA8 pixels of the renderer's size made on the CPU.
struct FrameSource {
    Renderer* renderer = nullptr;
    const std::vector<uint8_t>* pixels = nullptr; // used instead when not null
};

class Presenter {
public:
    Presenter(vk::Context& ctx, Swapchain& swapchain, Gui& gui);
    ~Presenter();
    Presenter(const Presenter&) = delete;
    Presenter& operator=(const Presenter&) = delete;

    // Draws and presents one frame (the panel's widgets must have been built). Returns false
    // when the swapchain no longer fits the window; the caller recreates it and draws again.
    // With `screenshot`, the whole window as presented (RGBA floats, rows top to bottom).
    bool draw(const FrameSource& source, VkRect2D sceneRect, std::vector<float>* screenshot);

private:
    void uploadPixels(VkCommandBuffer cmd, const std::vector<uint8_t>& pixels, VkExtent2D size);
    void readBack(VkCommandBuffer cmd, VkImage image, VkExtent2D extent);

    vk::Context& ctx_;
    Swapchain& swapchain_;
    Gui& gui_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    vk::Image cpuImage_; // the CPU-made view, copied in from cpuStaging_
    vk::Buffer cpuStaging_;
    vk::Buffer readback_; // the screenshot
};

} // namespace ssgi::viewer
