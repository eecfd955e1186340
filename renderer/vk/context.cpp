#include "vk/context.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

namespace ssgi::vk {

const char* resultName(VkResult result) {
    switch (result) {
#define CASE(x)                                                                                    \
    case x:                                                                                        \
        return #x;
        CASE(VK_SUCCESS)
        CASE(VK_NOT_READY)
        CASE(VK_TIMEOUT)
        CASE(VK_INCOMPLETE)
        CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        CASE(VK_ERROR_INITIALIZATION_FAILED)
        CASE(VK_ERROR_DEVICE_LOST)
        CASE(VK_ERROR_MEMORY_MAP_FAILED)
        CASE(VK_ERROR_LAYER_NOT_PRESENT)
        CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        CASE(VK_ERROR_TOO_MANY_OBJECTS)
        CASE(VK_ERROR_FRAGMENTED_POOL)
        CASE(VK_ERROR_UNKNOWN)
        CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        CASE(VK_ERROR_FRAGMENTATION)
        // Presentation (the viewer's swapchain and surface).
        CASE(VK_SUBOPTIMAL_KHR)
        CASE(VK_ERROR_OUT_OF_DATE_KHR)
        CASE(VK_ERROR_SURFACE_LOST_KHR)
        CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        CASE(VK_ERROR_INCOMPATIBLE_DISPLAY_KHR)
        CASE(VK_ERROR_VALIDATION_FAILED_EXT)
#undef CASE
    default: {
        // Any other code by its number, which the specification's VkResult table names: a
        // driver's failure to create a swapchain on an H200 under Xvfb printed "VkResult error"
        // and told nothing more. One buffer a thread, as the name is read before the next call.
        thread_local char text[32];
        std::snprintf(text, sizeof text, "VkResult %d", int(result));
        return text;
    }
    }
}

VkBool32 VKAPI_PTR Context::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                      VkDebugUtilsMessageTypeFlagsEXT,
                                      const VkDebugUtilsMessengerCallbackDataEXT* data,
                                      void* user) {
    auto* self = static_cast<Context*>(user);
    const char* level =
        (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    std::fprintf(stderr, "validation %s: %s\n", level, data->pMessage);
    self->validationMessages_++;
    return VK_FALSE;
}

static bool hasLayer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

static bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
    return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, name) == 0;
    });
}

// A device is usable when it speaks Vulkan 1.3, has a compute+graphics queue and push
// descriptors (and, with a surface, a swapchain and that queue able to present to it). Among
// usable devices, a discrete GPU wins unless a name is asked for.
static VkPhysicalDevice pickDevice(VkInstance instance, const std::string& wanted,
                                   VkSurfaceKHR surface, uint32_t& queueFamily) {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    VkPhysicalDevice best = VK_NULL_HANDLE;
    int bestScore = -1;
    std::string seen;
    for (VkPhysicalDevice device : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(device, &props);
        seen += std::string(seen.empty() ? "" : ", ") + props.deviceName;
        if (!wanted.empty() && std::string(props.deviceName).find(wanted) == std::string::npos)
            continue;
        if (props.apiVersion < VK_API_VERSION_1_3 ||
            !hasDeviceExtension(device, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
            continue;
        if (surface && !hasDeviceExtension(device, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) continue;
        VkPhysicalDeviceFeatures features;
        vkGetPhysicalDeviceFeatures(device, &features);
        if (!features.shaderStorageImageExtendedFormats ||
            !features.shaderStorageImageWriteWithoutFormat || !features.fragmentStoresAndAtomics)
            continue;
        // The temporal passes vote across a subgroup (temporal.comp: its pixels fall due together).
        VkPhysicalDeviceSubgroupProperties subgroup{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
        VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
        props2.pNext = &subgroup;
        vkGetPhysicalDeviceProperties2(device, &props2);
        if (!(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) ||
            !(subgroup.supportedOperations & VK_SUBGROUP_FEATURE_VOTE_BIT))
            continue;
        uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(device, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(device, &familyCount, families.data());
        for (uint32_t i = 0; i < familyCount; ++i) {
            const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
            if ((families[i].queueFlags & need) != need || families[i].timestampValidBits == 0)
                continue;
            VkBool32 present = VK_TRUE;
            if (surface) vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface, &present);
            if (!present) continue;
            int score = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU ? 2 : 1;
            if (score > bestScore) {
                best = device;
                bestScore = score;
                queueFamily = i;
            }
            break;
        }
    }
    if (best == VK_NULL_HANDLE) {
        std::string msg = "no usable Vulkan device";
        if (!wanted.empty()) msg += " named '" + wanted + "'";
        msg += " (need Vulkan 1.3, a graphics+compute queue with timestamps, "
               "VK_KHR_push_descriptor, storage images of half floats (rg16f), storage "
               "writes without a format and subgroup votes in compute shaders";
        msg += surface ? ", VK_KHR_swapchain and presentation to the window)" : ")";
        msg += seen.empty() ? "; no Vulkan device found at all (is mesa-vulkan-drivers installed?)"
                            : "; devices seen: " + seen;
        throw VulkanError(msg);
    }
    return best;
}

// What is wrong with the driver manifests the loader reads ($VK_DRIVER_FILES, else
// $VK_ICD_FILENAMES, else the system's icd.d folders), as "; manifest F: problem" each.
static std::string driverManifestProblems() {
    namespace fs = std::filesystem;
    std::vector<fs::path> files;
    const char* named = std::getenv("VK_DRIVER_FILES");
    if (!named || !*named) named = std::getenv("VK_ICD_FILENAMES");
    if (named && *named) {
        std::istringstream list(named);
        for (std::string item; std::getline(list, item, ':');)
            if (!item.empty()) files.emplace_back(item);
    } else {
        std::error_code ec;
        for (const char* folder :
             {"/etc/vulkan/icd.d", "/usr/share/vulkan/icd.d", "/usr/local/share/vulkan/icd.d"})
            for (const auto& entry : fs::directory_iterator(folder, ec))
                if (entry.path().extension() == ".json") files.push_back(entry.path());
    }
    std::string problems;
    for (const fs::path& file : files) {
        std::string problem;
        std::error_code ec;
        if (!fs::is_regular_file(file, ec)) {
            problem = fs::exists(file, ec) ? "not a regular file" : "not found";
        } else {
            std::ifstream in(file);
            const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
            if (manifest.is_discarded())
                problem = "not valid JSON";
            else if (!manifest.is_object() || !manifest.contains("ICD") ||
                     !manifest["ICD"].is_object() || !manifest["ICD"].contains("library_path") ||
                     !manifest["ICD"]["library_path"].is_string())
                problem = "no \"ICD\": {\"library_path\": ...} in it";
        }
        if (!problem.empty()) problems += "; manifest " + file.string() + ": " + problem;
    }
    return problems;
}

Context::Context(const ContextOptions& options) {
    const char* validationLayer = "VK_LAYER_KHRONOS_validation";
    validationEnabled = options.validation;
    if (validationEnabled && !hasLayer(validationLayer))
        throw VulkanError("validation requested but VK_LAYER_KHRONOS_validation is not installed "
                          "(Debian package vulkan-validationlayers)");

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "ssgi";
    app.apiVersion = VK_API_VERSION_1_3;
    std::vector<const char*> extensions = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    for (const std::string& e : options.instanceExtensions)
        extensions.push_back(e.c_str());

    VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                    VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = &Context::onMessage;
    messengerInfo.pUserData = this;
    features.pNext = &messengerInfo; // also catches messages from instance creation

    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pApplicationInfo = &app;
    instanceInfo.enabledExtensionCount = uint32_t(extensions.size());
    instanceInfo.ppEnabledExtensionNames = extensions.data();
    if (validationEnabled) {
        instanceInfo.enabledLayerCount = 1;
        instanceInfo.ppEnabledLayerNames = &validationLayer;
        instanceInfo.pNext = &features;
    }
    VkResult result = vkCreateInstance(&instanceInfo, nullptr, &instance);
    // The loader reports a malformed driver manifest as, among others, running out of memory:
    // the manifests are read here to say which one is wrong.
    if (result != VK_SUCCESS) {
        const std::string manifests = driverManifestProblems();
        if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED ||
            !manifests.empty())
            throw VulkanError("no Vulkan driver could be loaded (vkCreateInstance: " +
                              std::string(resultName(result)) + ")" +
                              (manifests.empty()
                                   ? "; on a machine without a GPU install mesa-vulkan-drivers"
                                   : manifests));
    }
    VK_CHECK(result);

    if (validationEnabled) {
        auto create = (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
            instance, "vkCreateDebugUtilsMessengerEXT");
        VK_CHECK(create(instance, &messengerInfo, nullptr, &messenger_));
    }
    cmdBeginLabel = (PFN_vkCmdBeginDebugUtilsLabelEXT)vkGetInstanceProcAddr(
        instance, "vkCmdBeginDebugUtilsLabelEXT");
    cmdEndLabel = (PFN_vkCmdEndDebugUtilsLabelEXT)vkGetInstanceProcAddr(
        instance, "vkCmdEndDebugUtilsLabelEXT");
    setObjectName = (PFN_vkSetDebugUtilsObjectNameEXT)vkGetInstanceProcAddr(
        instance, "vkSetDebugUtilsObjectNameEXT");

    if (options.createSurface) surface = options.createSurface(instance);
    physicalDevice = pickDevice(instance, options.deviceName, surface, queueFamily);
    vkGetPhysicalDeviceProperties(physicalDevice, &properties);
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &memoryProperties);
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props2.pNext = &driver;
    vkGetPhysicalDeviceProperties2(physicalDevice, &props2);
    driverName = std::string(driver.driverName) + " " + driver.driverInfo;

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    VkPhysicalDeviceVulkan13Features features13{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.dynamicRendering = VK_TRUE;
    features13.synchronization2 = VK_TRUE;
    features13.maintenance4 = VK_TRUE; // required in 1.3; SPIR-V for 1.3 uses LocalSizeId
    VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features2.pNext = &features13;
    // The caches' counts and the scalar effects' histories are rg16f (extended formats); the
    // temporal pass writes either kind of history through one binding (no format).
    features2.features.shaderStorageImageExtendedFormats = VK_TRUE;
    features2.features.shaderStorageImageWriteWithoutFormat = VK_TRUE;
    // The world cache's voxel grid is marked from fragment shaders (world_voxelize.frag).
    features2.features.fragmentStoresAndAtomics = VK_TRUE;
    // Where the device has them: the invocations each pass dispatched (FrameGraph, --profile).
    VkPhysicalDeviceFeatures available;
    vkGetPhysicalDeviceFeatures(physicalDevice, &available);
    pipelineStatistics = available.pipelineStatisticsQuery == VK_TRUE;
    features2.features.pipelineStatisticsQuery = available.pipelineStatisticsQuery;

    const char* deviceExtensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME,
                                      VK_KHR_SWAPCHAIN_EXTENSION_NAME};
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.pNext = &features2;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.enabledExtensionCount = surface ? 2 : 1;
    deviceInfo.ppEnabledExtensionNames = deviceExtensions;
    VK_CHECK(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device));
    vkGetDeviceQueue(device, queueFamily, 0, &queue);
    cmdPushDescriptorSet =
        (PFN_vkCmdPushDescriptorSetKHR)vkGetDeviceProcAddr(device, "vkCmdPushDescriptorSetKHR");

    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = queueFamily;
    VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &commandPool));
}

Context::~Context() {
    if (device) {
        vkDeviceWaitIdle(device);
        if (submitFence_) vkDestroyFence(device, submitFence_, nullptr);
        vkDestroyCommandPool(device, commandPool, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (messenger_) {
        auto destroy = (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
            instance, "vkDestroyDebugUtilsMessengerEXT");
        destroy(instance, messenger_, nullptr);
    }
    if (surface) vkDestroySurfaceKHR(instance, surface, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
}

HostSpan Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
    const bool nested = submitting_;
    VkCommandBuffer cmd = nested ? VK_NULL_HANDLE : submitCommands_;
    VkFence fence = nested ? VK_NULL_HANDLE : submitFence_;
    if (cmd == VK_NULL_HANDLE) {
        VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        allocInfo.commandPool = commandPool;
        allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        allocInfo.commandBufferCount = 1;
        VK_CHECK(vkAllocateCommandBuffers(device, &allocInfo, &cmd));
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VK_CHECK(vkCreateFence(device, &fenceInfo, nullptr, &fence));
        if (!nested) submitCommands_ = cmd, submitFence_ = fence;
    } else {
        VK_CHECK(vkResetCommandBuffer(cmd, 0));
        VK_CHECK(vkResetFences(device, 1, &fence));
    }
    struct Release { // the nested call's own buffer and fence go; the flag is cleared
        Context& ctx;
        bool nested;
        VkCommandBuffer cmd;
        VkFence fence;
        ~Release() {
            if (!nested) {
                ctx.submitting_ = false;
                return;
            }
            vkDestroyFence(ctx.device, fence, nullptr);
            vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &cmd);
        }
    } release{*this, nested, cmd, fence};
    submitting_ = true;

    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));

    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    VK_CHECK(vkQueueSubmit2(queue, 1, &submit, fence));
    VK_CHECK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
    const Clock::time_point end = Clock::now();
    using Us = std::chrono::duration<double, std::micro>;
    return {Us(start.time_since_epoch()).count(), Us(end - start).count() * 1e-3};
}

void Context::nameObject(VkObjectType type, uint64_t handle, const std::string& name) const {
    if (!setObjectName) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    setObjectName(device, &info);
}

} // namespace ssgi::vk
