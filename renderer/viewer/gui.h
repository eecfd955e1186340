// Dear ImGui on the window: its context, the GLFW input backend and the Vulkan drawing backend
// (Debian's libimgui-dev ships both), drawn inside the swapchain's render pass.
#pragma once

#include "viewer/swapchain.h"

struct GLFWwindow;

namespace ssgi::viewer {

class Gui {
public:
    Gui(vk::Context& ctx, GLFWwindow* window, const Swapchain& swapchain);
    ~Gui();
    Gui(const Gui&) = delete;
    Gui& operator=(const Gui&) = delete;

    // Starts a frame of widgets (input from GLFW); the panel's ImGui calls follow.
    void beginFrame();
    // Ends the frame's widgets and records their drawing into cmd (inside the render pass).
    void record(VkCommandBuffer cmd);
    // Ends the frame's widgets without drawing them (the frame was not presented).
    void cancelFrame();
    // Whether ImGui takes the mouse / keyboard this frame (the fly camera must not).
    bool wantsMouse() const;
    bool wantsKeyboard() const;

private:
    vk::Context& ctx_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
};

} // namespace ssgi::viewer
