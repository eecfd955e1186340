// The Vulkan instance, device and queue: Vulkan 1.3 with dynamic rendering, synchronization2
// and push descriptors. Picks a discrete GPU when present, else the first device (lavapipe on a
// machine without a GPU); a name substring (flag or SSGI_DEVICE) selects one explicitly.
#pragma once

#include <vulkan/vulkan.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ssgi::vk {

// A Vulkan call failed, or no usable device exists. The message names the call.
struct VulkanError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

const char* resultName(VkResult result);

#define VK_CHECK(call)                                                                             \
    do {                                                                                           \
        VkResult vkCheckResult_ = (call);                                                          \
        if (vkCheckResult_ != VK_SUCCESS)                                                          \
            throw ::ssgi::vk::VulkanError(std::string(#call) +                                     \
                                          " failed: " + ::ssgi::vk::resultName(vkCheckResult_));   \
    } while (0)

// A span of host time around a submission.
struct HostSpan {
    double startUs = 0.0;
    double milliseconds = 0.0;
};

struct ContextOptions {
    bool validation = false; // Khronos validation layer with synchronization validation
    std::string deviceName;  // substring of the device name to pick; empty = automatic
    // For a window (the viewer): the instance extensions its surface needs, and a function that
    // creates the surface once the instance exists. With one, the device must be able to present
    // to it from its queue and VK_KHR_swapchain is enabled. Headless programs leave both empty.
    std::vector<std::string> instanceExtensions;
    std::function<VkSurfaceKHR(VkInstance)> createSurface;
};

class Context {
public:
    explicit Context(const ContextOptions& options);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkSurfaceKHR surface = VK_NULL_HANDLE; // only with ContextOptions::createSurface
    VkCommandPool commandPool = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memoryProperties{};
    std::string driverName; // e.g. "llvmpipe" + driver info
    bool validationEnabled = false;
    // Pipeline statistics queries are on (the device has them): the frame graph counts the
    // compute invocations each pass dispatched.
    bool pipelineStatistics = false;

    // Validation messages (warnings and errors) seen so far; tests require zero.
    uint32_t validationMessageCount() const { return validationMessages_; }

    // Records with `record` into a command buffer, submits and waits. The command buffer and the
    // fence are made once and reused: made and destroyed at every frame, they grew the
    // validation layer's bookkeeping with every frame.
    // Returns the host's view of the submission: when it was made (microseconds on the steady
    // clock) and how long until the fence signalled (milliseconds).
    HostSpan submitAndWait(const std::function<void(VkCommandBuffer)>& record);

    // Debug-utils entry points (null when the extension is absent).
    PFN_vkCmdBeginDebugUtilsLabelEXT cmdBeginLabel = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT cmdEndLabel = nullptr;
    PFN_vkSetDebugUtilsObjectNameEXT setObjectName = nullptr;
    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

    void nameObject(VkObjectType type, uint64_t handle, const std::string& name) const;

private:
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    uint32_t validationMessages_ = 0;
    VkCommandBuffer submitCommands_ = VK_NULL_HANDLE; // submitAndWait's, reset at each use
    VkFence submitFence_ = VK_NULL_HANDLE;
    bool submitting_ = false; // a submitAndWait within another's `record` gets its own
    static VkBool32 VKAPI_PTR onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                        VkDebugUtilsMessageTypeFlagsEXT types,
                                        const VkDebugUtilsMessengerCallbackDataEXT* data,
                                        void* user);
};

} // namespace ssgi::vk
