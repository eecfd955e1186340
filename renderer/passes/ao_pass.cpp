// ao: screen-space ambient occlusion from the G-buffer (thesis 3.2; Mittring; GTAO).
#include "passes/pass_setup.h"

#include "shared.h"

namespace ssgi {

graph::ImageRef addAoPass(PassSetup& s, const GBufferAndRsm& in, EffectCache* cache) {
    graph::ImageRef ao = s.graph.createImage(
        "ao", VK_FORMAT_R16G16B16A16_SFLOAT, s.size,
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    const Scene& m = s.model;
    const CacheInputs history = cacheInputs(s, cache, in.gbuffer.viewDepth);

    addKeepPass(s, cache, {ao});
    using graph::Use;
    ComputePassDesc pass{"ao", "ao.comp"};
    pass.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"historyViewDepth", history.viewDepth, Use::Sampled},
                   {"historyCount", history.count, Use::Sampled},
                   {"aoImage", ao, Use::StorageWrite}};
    pass.pushSize = sizeof(shader::AoConstants);
    pass.spec = {
        {int(m.settings.ao_variant), int(m.settings.ao_directions), int(m.settings.ao_steps)}};
    addComputePass(s, std::move(pass), [&s, cache](const ComputeRecorder& r) {
        shader::AoConstants constants{};
        constants.rotation = s.patternRotation;
        constants.scale = s.patternScale;
        constants.radius = aoRadius(s.model);
        constants.radialOffset = radialOffset(s, cache);
        constants.falloffA = float(s.model.settings.ao_attenuation_a);
        constants.falloffB = float(s.model.settings.ao_attenuation_b);
        constants.cache = cacheConstants(s, cache);
        const VkExtent2D area = cacheDispatch(s, cache, s.size);
        r.dispatch(area.width, area.height, constants);
    });
    return ao;
}

} // namespace ssgi
