// Rasterises the whole scene into three colour targets and a depth target (G-buffer, RSM).
#include "passes/pass_setup.h"

#include "shared.h"

namespace ssgi {

SceneTargets addScenePass(PassSetup& s, const std::string& name, const std::string& shader,
                          VkExtent2D extent, bool viewDepth, VkFormat thirdFormat,
                          std::function<bool()> enabled,
                          std::optional<uint32_t>* viewDepthHistory) {
    const bool persistent = bool(enabled);
    const VkImageUsageFlags color =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    SceneTargets t;
    auto target = [&](const std::string& suffix, VkFormat format, VkImageUsageFlags usage) {
        return s.graph.createImage(name + suffix, format, extent, usage, persistent);
    };
    const VkFormat firstFormat = viewDepth ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT;
    graph::ImageRef& first = viewDepth ? t.viewDepth : t.position;
    const std::string firstName = viewDepth ? ".view_depth" : ".position";
    if (viewDepthHistory) {
        *viewDepthHistory = s.graph.createHistory(name + firstName, firstFormat, extent, color);
        first = graph::FrameGraph::current(**viewDepthHistory);
    } else {
        first = target(firstName, firstFormat, color);
    }
    t.normal = target(".normal", VK_FORMAT_R16G16B16A16_SFLOAT, color);
    t.third =
        target(thirdFormat == VK_FORMAT_R8G8B8A8_UNORM ? ".albedo" : ".flux", thirdFormat, color);
    t.depth = target(".depth", VK_FORMAT_D32_SFLOAT,
                     VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);

    vk::GraphicsPipelineDesc desc;
    desc.vertices = sceneVertexInput();
    desc.vertexShader = shader + ".vert";
    desc.fragmentShader = shader + ".frag";
    desc.colorFormats = {firstFormat, VK_FORMAT_R16G16B16A16_SFLOAT, thirdFormat};
    desc.depthFormat = VK_FORMAT_D32_SFLOAT;
    desc.bindings = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, "FrameBlock"},
                     {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, "baseColorTexture"}};
    desc.pushConstantSize = sizeof(shader::DrawConstants);
    s.pipelines.push_back(vk::createGraphicsPipeline(s.ctx, desc));
    const vk::Pipeline pipeline = s.pipelines.back();

    using graph::Use;
    s.graph.addPass(
        name, graph::PassKind::Graphics,
        {{first, Use::ColorAttachment},
         {t.normal, Use::ColorAttachment},
         {t.third, Use::ColorAttachment},
         {t.depth, Use::DepthAttachment}},
        [&s, t, extent, pipeline, viewDepth](const graph::PassContext& pc) {
            VkRenderingAttachmentInfo colors[3];
            const graph::ImageRef refs[3] = {viewDepth ? t.viewDepth : t.position, t.normal,
                                             t.third};
            for (int i = 0; i < 3; ++i) {
                colors[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
                colors[i].imageView = pc.image(refs[i]).view;
                colors[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
                colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR; // 0 marks "no geometry"
                colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            }
            VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            depth.imageView = pc.image(t.depth).view;
            depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
            depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            depth.clearValue.depthStencil = {1.0f, 0};
            VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
            info.renderArea = {{0, 0}, extent};
            info.layerCount = 1;
            info.colorAttachmentCount = 3;
            info.pColorAttachments = colors;
            info.pDepthAttachment = &depth;
            vkCmdBeginRendering(pc.cmd, &info);
            VkViewport viewport{0, 0, float(extent.width), float(extent.height), 0, 1};
            VkRect2D scissor{{0, 0}, extent};
            vkCmdSetViewport(pc.cmd, 0, 1, &viewport);
            vkCmdSetScissor(pc.cmd, 0, 1, &scissor);
            s.scene.draw(pc.cmd, pipeline, s.frameUniforms.buffer, s.frameUniforms.size);
            vkCmdEndRendering(pc.cmd);
        },
        enabled);
    return t;
}

} // namespace ssgi
