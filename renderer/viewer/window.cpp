#include "viewer/window.h"

#include <GLFW/glfw3.h>

#include <cstdlib>

namespace ssgi::viewer {

namespace {

std::string lastGlfwError() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "no detail";
}

// GLFW is initialised once per process, by the first window.
void initGlfw() {
    static bool initialised = false;
    if (initialised) return;
    if (!glfwInit()) {
        const std::string detail = lastGlfwError();
        const char* display = std::getenv("DISPLAY");
        const char* wayland = std::getenv("WAYLAND_DISPLAY");
        std::string where = (display && *display) || (wayland && *wayland)
                                ? std::string("DISPLAY=") + (display ? display : "") +
                                      " WAYLAND_DISPLAY=" + (wayland ? wayland : "")
                                : "neither DISPLAY nor WAYLAND_DISPLAY is set";
        throw WindowError("cannot open a window: " + detail + " (" + where +
                          "; without a screen run the viewer under xvfb-run)");
    }
    initialised = true;
    std::atexit([] { glfwTerminate(); });
    if (!glfwVulkanSupported())
        throw WindowError("GLFW found no Vulkan loader able to present to a window "
                          "(install libvulkan1 and mesa-vulkan-drivers)");
}

} // namespace

Window::Window(uint32_t width, uint32_t height, const std::string& title) {
    initGlfw();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (!window_) throw WindowError("cannot create a window: " + lastGlfwError());
    // A frame can take seconds on a software device: a key tapped between two frames still
    // reads as pressed at the next one.
    glfwSetInputMode(window_, GLFW_STICKY_KEYS, GLFW_TRUE);
    glfwSetInputMode(window_, GLFW_STICKY_MOUSE_BUTTONS, GLFW_TRUE);
}

Window::~Window() {
    if (window_) glfwDestroyWindow(window_);
}

std::vector<std::string> Window::requiredInstanceExtensions() {
    initGlfw();
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names)
        throw WindowError("this window system cannot present Vulkan images: " + lastGlfwError());
    return std::vector<std::string>(names, names + count);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) const {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkResult result = glfwCreateWindowSurface(instance, window_, nullptr, &surface);
    if (result != VK_SUCCESS)
        throw WindowError("cannot create a Vulkan surface for the window: " + lastGlfwError());
    return surface;
}

VkExtent2D Window::framebufferSize() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED)) w = h = 0;
    return {uint32_t(w), uint32_t(h)};
}

bool Window::shouldClose() const {
    return glfwWindowShouldClose(window_);
}

void Window::requestClose() {
    glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

void Window::setSize(uint32_t width, uint32_t height) {
    glfwSetWindowSize(window_, int(width), int(height));
}

void Window::setTitle(const std::string& title) {
    glfwSetWindowTitle(window_, title.c_str());
}

void Window::pollEvents() {
    glfwPollEvents();
    while (!shouldClose()) {
        const VkExtent2D size = framebufferSize();
        if (size.width > 0 && size.height > 0) break;
        glfwWaitEvents();
    }
}

} // namespace ssgi::viewer
