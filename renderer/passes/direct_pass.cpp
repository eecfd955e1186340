// direct: radiance from the spot light at every G-buffer pixel, times the shadow term.
#include "passes/pass_setup.h"

namespace ssgi {

graph::ImageRef addDirectPass(PassSetup& s, const GBufferAndRsm& in, graph::ImageRef shadow) {
    graph::ImageRef direct =
        s.graph.createImage("direct", VK_FORMAT_R16G16B16A16_SFLOAT, s.size,
                            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    const VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    s.pipelines.push_back(
        vk::createComputePipeline(s.ctx, "direct.comp",
                                  {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, sampled, sampled, sampled,
                                   sampled, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                                  0));
    const vk::Pipeline pipeline = s.pipelines.back();

    using graph::Use;
    s.graph.addPass("direct", graph::PassKind::Compute,
                    {{in.gbuffer.position, Use::Sampled},
                     {in.gbuffer.normal, Use::Sampled},
                     {in.gbuffer.third, Use::Sampled},
                     {shadow, Use::Sampled},
                     {direct, Use::StorageWrite}},
                    [&s, in, shadow, direct, pipeline](const graph::PassContext& pc) {
                        vk::Descriptors()
                            .uniformBuffer(0, s.frameUniforms.buffer, s.frameUniforms.size)
                            .sampledImage(1, pc.image(in.gbuffer.position).view, s.nearestSampler)
                            .sampledImage(2, pc.image(in.gbuffer.normal).view, s.nearestSampler)
                            .sampledImage(3, pc.image(in.gbuffer.third).view, s.nearestSampler)
                            .sampledImage(4, pc.image(shadow).view, s.nearestSampler)
                            .storageImage(5, pc.image(direct).view)
                            .push(s.ctx, pc.cmd, pipeline);
                        vk::dispatch(pc.cmd, pipeline, s.size.width, s.size.height, nullptr, 0);
                    });
    return direct;
}

} // namespace ssgi
