// composite: the frame's terms added up into HDR radiance, then tonemapped to an sRGB image
// (or a debug view of any intermediate in its place).
#include "passes/pass_setup.h"

#include "shared.h"

namespace ssgi {

CompositeOutputs addCompositePass(PassSetup& s, const GBufferAndRsm& in, graph::ImageRef direct,
                                  int view) {
    const VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    CompositeOutputs out;
    out.hdr = s.graph.createImage("hdr", VK_FORMAT_R32G32B32A32_SFLOAT, s.size, storage);
    out.ldr = s.graph.createImage("ldr", VK_FORMAT_R8G8B8A8_UNORM, s.size, storage);
    const VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    const VkDescriptorType image = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    s.pipelines.push_back(
        vk::createComputePipeline(s.ctx, "composite.comp",
                                  {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, sampled, sampled, sampled,
                                   sampled, sampled, sampled, image, image},
                                  sizeof(shader::CompositeConstants)));
    const vk::Pipeline pipeline = s.pipelines.back();

    using graph::Use;
    s.graph.addPass("composite", graph::PassKind::Compute,
                    {{in.gbuffer.position, Use::Sampled},
                     {in.gbuffer.normal, Use::Sampled},
                     {in.gbuffer.third, Use::Sampled},
                     {direct, Use::Sampled},
                     {in.rsm.third, Use::Sampled},
                     {in.rsm.normal, Use::Sampled},
                     {out.hdr, Use::StorageWrite},
                     {out.ldr, Use::StorageWrite}},
                    [&s, in, direct, out, pipeline, view](const graph::PassContext& pc) {
                        vk::Descriptors()
                            .uniformBuffer(0, s.frameUniforms.buffer, s.frameUniforms.size)
                            .sampledImage(1, pc.image(in.gbuffer.position).view, s.nearestSampler)
                            .sampledImage(2, pc.image(in.gbuffer.normal).view, s.nearestSampler)
                            .sampledImage(3, pc.image(in.gbuffer.third).view, s.nearestSampler)
                            .sampledImage(4, pc.image(direct).view, s.nearestSampler)
                            .sampledImage(5, pc.image(in.rsm.third).view, s.linearSampler)
                            .sampledImage(6, pc.image(in.rsm.normal).view, s.nearestSampler)
                            .storageImage(7, pc.image(out.hdr).view)
                            .storageImage(8, pc.image(out.ldr).view)
                            .push(s.ctx, pc.cmd, pipeline);
                        shader::CompositeConstants constants{};
                        constants.mode.x = view;
                        vk::dispatch(pc.cmd, pipeline, s.size.width, s.size.height, constants);
                    });
    return out;
}

} // namespace ssgi
