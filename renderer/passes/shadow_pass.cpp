// shadow: how much of the spot light's disk each G-buffer pixel sees, by percentage-closer
// filtering of the RSM depth with a kernel sized from the disk (thesis 3.4, PCSS).
#include "passes/pass_setup.h"

#include "shared.h"

namespace ssgi {

graph::ImageRef addShadowPass(PassSetup& s, const GBufferAndRsm& in, EffectCache* cache) {
    graph::ImageRef shadow = s.graph.createImage(
        "shadow", VK_FORMAT_R16G16B16A16_SFLOAT, s.size,
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    const int taps = int(s.model.settings.shadow_taps);
    const vk::Pipeline pipeline =
        s.computePipeline("shadow.comp", 5, 1, sizeof(shader::ShadowConstants), {{taps}});

    const CacheInputs history = cacheInputs(s, cache, in.gbuffer.position);
    addKeepPass(s, cache, {shadow});
    using graph::Use;
    s.graph.addPass("shadow", graph::PassKind::Compute,
                    {{in.gbuffer.position, Use::Sampled},
                     {in.gbuffer.normal, Use::Sampled},
                     {in.rsm.depth, Use::Sampled},
                     {history.position, Use::Sampled},
                     {history.count, Use::Sampled},
                     {shadow, Use::StorageWrite}},
                    [&s, in, shadow, history, cache, pipeline](const graph::PassContext& pc) {
                        vk::Descriptors()
                            .uniformBuffer(0, s.frameUniforms.buffer, s.frameUniforms.size)
                            .sampledImage(1, pc.image(in.gbuffer.position).view, s.nearestSampler)
                            .sampledImage(2, pc.image(in.gbuffer.normal).view, s.nearestSampler)
                            .sampledImage(3, pc.image(in.rsm.depth).view, s.nearestSampler)
                            .sampledImage(4, pc.image(history.position).view, s.nearestSampler)
                            .sampledImage(5, pc.image(history.count).view, s.nearestSampler)
                            .storageImage(6, pc.image(shadow).view)
                            .push(s.ctx, pc.cmd, pipeline);
                        shader::ShadowConstants constants{};
                        constants.rotation = s.patternRotation;
                        constants.scale = s.patternScale;
                        constants.normalOffset = float(s.model.settings.shadow_bias);
                        constants.radialOffset = radialOffset(s, cache);
                        constants.cache = cacheConstants(s, cache);
                        const VkExtent2D area = cacheDispatch(s, cache, s.size);
                        vk::dispatch(pc.cmd, pipeline, area.width, area.height, constants);
                    });
    return shadow;
}

} // namespace ssgi
