// The desktop window (GLFW, no client API: Vulkan draws into it through a swapchain). Opening it
// fails with a clear message when there is no display to open it on.
#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>
#include <vector>

struct GLFWwindow;

namespace ssgi::viewer {

// No display, no window system, or no Vulkan loader that can present: the viewer cannot run.
struct WindowError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Window {
public:
    Window(uint32_t width, uint32_t height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    // The instance extensions a surface for this window needs (VK_KHR_surface + the platform's).
    static std::vector<std::string> requiredInstanceExtensions();
    VkSurfaceKHR createSurface(VkInstance instance) const;

    GLFWwindow* handle() const { return window_; }
    // Pixels of the drawable area; 0 x 0 while minimised.
    VkExtent2D framebufferSize() const;
    bool shouldClose() const;
    void requestClose();
    void setSize(uint32_t width, uint32_t height);
    void setTitle(const std::string& title);
    // Handles pending events; while minimised, sleeps in the event loop until the window is
    // shown again (or asked to close).
    void pollEvents();

private:
    GLFWwindow* window_ = nullptr;
};

} // namespace ssgi::viewer
