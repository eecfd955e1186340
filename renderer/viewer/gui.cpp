#include "viewer/gui.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

namespace ssgi::viewer {

namespace {

void checkResult(VkResult result) {
    if (result != VK_SUCCESS)
        throw vk::VulkanError(std::string("ImGui's Vulkan backend: ") + vk::resultName(result));
}

} // namespace

Gui::Gui(vk::Context& ctx, GLFWwindow* window, const Swapchain& swapchain) : ctx_(ctx) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini beside wherever the viewer was started
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 0.0f;

    // The font atlas is the only texture ImGui samples.
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    poolInfo.maxSets = 4;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    VK_CHECK(vkCreateDescriptorPool(ctx.device, &poolInfo, nullptr, &pool_));

    ImGui_ImplGlfw_InitForVulkan(window, true);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = ctx.instance;
    info.PhysicalDevice = ctx.physicalDevice;
    info.Device = ctx.device;
    info.QueueFamily = ctx.queueFamily;
    info.Queue = ctx.queue;
    info.DescriptorPool = pool_;
    info.Subpass = 0;
    // ImGui keeps one vertex buffer per image; the viewer has one frame in flight at a time, so
    // the count only has to satisfy the backend, not follow the swapchain.
    info.MinImageCount = 2;
    info.ImageCount = 2;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = checkResult;
    ImGui_ImplVulkan_Init(&info, swapchain.renderPass());
    ctx.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

Gui::~Gui() {
    vkDeviceWaitIdle(ctx_.device);
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    vkDestroyDescriptorPool(ctx_.device, pool_, nullptr);
}

void Gui::beginFrame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void Gui::record(VkCommandBuffer cmd) {
    ImGui::Render();
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
}

void Gui::cancelFrame() {
    ImGui::EndFrame();
}

bool Gui::wantsMouse() const {
    return ImGui::GetIO().WantCaptureMouse;
}

bool Gui::wantsKeyboard() const {
    return ImGui::GetIO().WantCaptureKeyboard;
}

} // namespace ssgi::viewer
