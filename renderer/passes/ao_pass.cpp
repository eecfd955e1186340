// ao: screen-space ambient occlusion from the G-buffer (thesis 3.2; Mittring; GTAO).
#include "passes/pass_setup.h"

#include "shared.h"

namespace ssgi {

graph::ImageRef addAoPass(PassSetup& s, const GBufferAndRsm& in, EffectCache* cache) {
    graph::ImageRef ao = s.graph.createImage(
        "ao", VK_FORMAT_R16G16B16A16_SFLOAT, s.size,
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    const Scene& m = s.model;
    const vk::Pipeline pipeline = s.computePipeline(
        "ao.comp", 4, 1, sizeof(shader::AoConstants),
        {{int(m.settings.ao_variant), int(m.settings.ao_directions), int(m.settings.ao_steps)}});
    const CacheInputs history = cacheInputs(s, cache, in.gbuffer.position);

    addKeepPass(s, cache, {ao});
    using graph::Use;
    s.graph.addPass("ao", graph::PassKind::Compute,
                    {{in.gbuffer.position, Use::Sampled},
                     {in.gbuffer.normal, Use::Sampled},
                     {history.position, Use::Sampled},
                     {history.count, Use::Sampled},
                     {ao, Use::StorageWrite}},
                    [&s, in, ao, history, cache, pipeline](const graph::PassContext& pc) {
                        vk::Descriptors()
                            .uniformBuffer(0, s.frameUniforms.buffer, s.frameUniforms.size)
                            .sampledImage(1, pc.image(in.gbuffer.position).view, s.nearestSampler)
                            .sampledImage(2, pc.image(in.gbuffer.normal).view, s.nearestSampler)
                            .sampledImage(3, pc.image(history.position).view, s.nearestSampler)
                            .sampledImage(4, pc.image(history.count).view, s.nearestSampler)
                            .storageImage(5, pc.image(ao).view)
                            .push(s.ctx, pc.cmd, pipeline);
                        shader::AoConstants constants{};
                        constants.rotation = s.patternRotation;
                        constants.scale = s.patternScale;
                        constants.radius = aoRadius(s.model);
                        constants.radialOffset = radialOffset(s, cache);
                        constants.falloffA = float(s.model.settings.ao_attenuation_a);
                        constants.falloffB = float(s.model.settings.ao_attenuation_b);
                        constants.cache = cacheConstants(s, cache);
                        const VkExtent2D area = cacheDispatch(s, cache, s.size);
                        vk::dispatch(pc.cmd, pipeline, area.width, area.height, constants);
                    });
    return ao;
}

} // namespace ssgi
