// Rasterises the whole scene into its colour targets and a depth target (G-buffer, RSM).
#include "passes/scene_pass.h"

#include "shared.h"

namespace ssgi {

vk::GraphicsPipelineDesc depthOnly(vk::GraphicsPipelineDesc desc) {
    desc.fragmentShader.clear();
    desc.bindings = {desc.bindings[0]};
    return desc;
}

SceneTargets addScenePass(FrameBuild& build, const std::string& name, const std::string& shader,
                          VkExtent2D extent, const std::vector<SceneTarget>& targets,
                          graph::EnabledFn enabled, std::optional<uint32_t>* firstTargetHistory,
                          OpaqueDraws opaqueDraws, DepthTarget depthTarget) {
    const bool persistent = bool(enabled);
    const VkImageUsageFlags color =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    SceneTargets t;
    // The colour targets in the fragment shader's order.
    std::vector<VkFormat> formats;
    for (const SceneTarget& target : targets) {
        const std::string image = name + target.suffix;
        if (firstTargetHistory && t.colors.empty()) {
            *firstTargetHistory = build.graph.createHistory(image, target.format, extent, color);
            t.colors.push_back(graph::FrameGraph::current(**firstTargetHistory));
        } else {
            t.colors.push_back(
                build.graph.createImage(image, target.format, extent, color, persistent));
        }
        formats.push_back(target.format);
    }
    t.depth = build.graph.createImage(name + ".depth", VK_FORMAT_D32_SFLOAT, extent,
                                      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                          VK_IMAGE_USAGE_SAMPLED_BIT,
                                      persistent && depthTarget == DepthTarget::Read);

    vk::GraphicsPipelineDesc desc;
    desc.vertices = sceneVertexInput();
    desc.vertexShader = shader + ".vert";
    desc.fragmentShader = shader + ".frag";
    desc.colorFormats = formats;
    desc.depthFormat = VK_FORMAT_D32_SFLOAT;
    desc.bindings = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, "FrameBlock"},
                     {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, "baseColorTexture"}};
    desc.pushConstantSize = sizeof(shader::DrawConstants);
    const vk::Pipeline masked = build.graphicsPipeline(desc);
    // A fragment shader that may discard keeps llvmpipe from testing depth before it runs: it
    // runs for every fragment, the opaque ones' too. With none at all their depth is tested and
    // written without it: shadow_map (lavapipe, 256x256, uncached) 62 -> 26 ms on the bunny,
    // 141 -> 60 on Sponza, 40 -> 8 on the scrub pine; the images bit-identical.
    const vk::Pipeline opaque =
        opaqueDraws == OpaqueDraws::DepthOnly ? build.graphicsPipeline(depthOnly(desc)) : masked;

    using graph::Use;
    std::vector<graph::ImageUse> uses;
    for (const graph::ImageRef& c : t.colors)
        uses.push_back({c, Use::ColorAttachment});
    uses.push_back({t.depth, Use::DepthAttachment});
    build.graph.addPass(
        name, graph::PassKind::Graphics, uses,
        [&build, t, extent, opaque, masked](const graph::PassContext& pc) {
            std::vector<VkRenderingAttachmentInfo> attachments;
            for (const graph::ImageRef& c : t.colors) {
                VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
                a.imageView = pc.image(c).view;
                a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
                a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR; // 0 marks "no geometry"
                a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
                attachments.push_back(a);
            }
            VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            depth.imageView = pc.image(t.depth).view;
            depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
            depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            depth.clearValue.depthStencil = {1.0f, 0}; // the far plane
            VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
            info.renderArea = {{0, 0}, extent};
            info.layerCount = 1;
            info.colorAttachmentCount = uint32_t(attachments.size());
            info.pColorAttachments = attachments.data();
            info.pDepthAttachment = &depth;
            vkCmdBeginRendering(pc.cmd, &info);
            VkViewport viewport{0, 0, float(extent.width), float(extent.height), 0, 1};
            VkRect2D scissor{{0, 0}, extent};
            vkCmdSetViewport(pc.cmd, 0, 1, &viewport);
            vkCmdSetScissor(pc.cmd, 0, 1, &scissor);
            build.sceneGpu.draw(pc.cmd, opaque, masked, build.frameUniforms.buffer,
                                build.frameUniforms.size);
            vkCmdEndRendering(pc.cmd);
        },
        enabled);
    return t;
}

} // namespace ssgi
