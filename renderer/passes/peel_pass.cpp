// peel: the second depth layer for SSDO's occlusion test (SSDO paper section 4): the scene drawn
// again, keeping only what lies behind the G-buffer's surface.
#include "passes/passes.h"

#include "shared.h"

namespace ssgi {

graph::ImageRef addPeelPass(FrameBuild& build, const GBufferAndRsm& in) {
    const graph::ImageRef position =
        build.graph.createImage("peel.position", VK_FORMAT_R32G32B32A32_SFLOAT, build.size,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    const graph::ImageRef depth = build.graph.createImage(
        "peel.depth", VK_FORMAT_D32_SFLOAT, build.size,
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    vk::GraphicsPipelineDesc desc;
    desc.vertices = sceneVertexInput();
    desc.vertexShader = "gbuffer.vert";
    desc.fragmentShader = "peel.frag";
    desc.colorFormats = {VK_FORMAT_R32G32B32A32_SFLOAT};
    desc.depthFormat = VK_FORMAT_D32_SFLOAT;
    desc.bindings = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, "FrameBlock"},
                     {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, "baseColorTexture"},
                     {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, "firstLayerViewDepth"}};
    desc.pushConstantSize = sizeof(shader::DrawConstants);
    const vk::Pipeline pipeline = build.graphicsPipeline(desc);

    using graph::Use;
    build.graph.addPass(
        "peel", graph::PassKind::Graphics,
        {{in.gbuffer.viewDepth, Use::Sampled},
         {position, Use::ColorAttachment},
         {depth, Use::DepthAttachment}},
        [&build, in, position, depth, pipeline](const graph::PassContext& pc) {
            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = pc.image(position).view;
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR; // w = 0: no second layer
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            VkRenderingAttachmentInfo depthInfo{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            depthInfo.imageView = pc.image(depth).view;
            depthInfo.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
            depthInfo.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            depthInfo.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
            depthInfo.clearValue.depthStencil = {1.0f, 0};
            VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
            info.renderArea = {{0, 0}, build.size};
            info.layerCount = 1;
            info.colorAttachmentCount = 1;
            info.pColorAttachments = &color;
            info.pDepthAttachment = &depthInfo;
            vkCmdBeginRendering(pc.cmd, &info);
            VkViewport viewport{0, 0, float(build.size.width), float(build.size.height), 0, 1};
            VkRect2D scissor{{0, 0}, build.size};
            vkCmdSetViewport(pc.cmd, 0, 1, &viewport);
            vkCmdSetScissor(pc.cmd, 0, 1, &scissor);
            const VkImageView first = pc.image(in.gbuffer.viewDepth).view;
            build.sceneGpu.draw(
                pc.cmd, pipeline, build.frameUniforms.buffer, build.frameUniforms.size,
                [&](vk::Descriptors& d) { d.sampledImage(2, first, build.nearestSampler); });
            vkCmdEndRendering(pc.cmd);
        });
    return position;
}

ShaderImage secondLayerInput(const GBufferAndRsm& in) {
    return {"secondLayer", in.secondLayer.valid() ? in.secondLayer : in.gbuffer.viewDepth,
            graph::Use::Sampled};
}

} // namespace ssgi
