// ssdo: screen-space directional occlusion of the sky plus one bounce of the direct-lit frame
// (Ritschel et al. 2009); replaces sky x AO in the composite when on.
#include "passes/pass_setup.h"

#include "shared.h"

namespace ssgi {

graph::ImageRef addSsdoPass(PassSetup& s, const GBufferAndRsm& in, graph::ImageRef direct,
                            graph::ImageRef secondLayer, EffectCache* cache) {
    graph::ImageRef ssdo = s.graph.createImage(
        "ssdo", VK_FORMAT_R16G16B16A16_SFLOAT, s.size,
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    const vk::Pipeline pipeline =
        s.computePipeline("ssdo.comp", 7, 1, sizeof(shader::SsdoConstants),
                          {{int(s.model.settings.ssdo_samples), secondLayer.valid() ? 1 : 0}});
    // Without peeling the shader never reads its second-layer binding: any valid image will do.
    const graph::ImageRef back = secondLayer.valid() ? secondLayer : in.gbuffer.position;
    const double radius = s.model.settings.ssdo_radius;
    const float rMax = radius > 0.0 ? float(radius) : aoRadius(s.model);

    const CacheInputs history = cacheInputs(s, cache, in.gbuffer.position);
    addKeepPass(s, cache, {ssdo});
    using graph::Use;
    s.graph.addPass(
        "ssdo", graph::PassKind::Compute,
        {{in.gbuffer.position, Use::Sampled},
         {in.gbuffer.normal, Use::Sampled},
         {in.gbuffer.third, Use::Sampled},
         {direct, Use::Sampled},
         {history.position, Use::Sampled},
         {history.count, Use::Sampled},
         {back, Use::Sampled},
         {ssdo, Use::StorageWrite}},
        [&s, in, direct, ssdo, history, back, cache, pipeline, rMax](const graph::PassContext& pc) {
            vk::Descriptors()
                .uniformBuffer(0, s.frameUniforms.buffer, s.frameUniforms.size)
                .sampledImage(1, pc.image(in.gbuffer.position).view, s.nearestSampler)
                .sampledImage(2, pc.image(in.gbuffer.normal).view, s.nearestSampler)
                .sampledImage(3, pc.image(in.gbuffer.third).view, s.nearestSampler)
                .sampledImage(4, pc.image(direct).view, s.nearestSampler)
                .sampledImage(5, pc.image(history.position).view, s.nearestSampler)
                .sampledImage(6, pc.image(history.count).view, s.nearestSampler)
                .sampledImage(7, pc.image(back).view, s.nearestSampler)
                .storageImage(8, pc.image(ssdo).view)
                .push(s.ctx, pc.cmd, pipeline);
            shader::SsdoConstants constants{};
            constants.rotation = s.patternRotation;
            constants.scale = s.patternScale;
            constants.rMax = rMax;
            constants.bounceStrength = float(s.model.settings.ssdo_bounce);
            constants.cache = cacheConstants(s, cache);
            const VkExtent2D area = cacheDispatch(s, cache, s.size);
            vk::dispatch(pc.cmd, pipeline, area.width, area.height, constants);
        });
    return ssdo;
}

} // namespace ssgi
