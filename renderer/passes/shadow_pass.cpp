// shadow: how much of the spot light's disk each G-buffer pixel sees, by percentage-closer
// filtering of the RSM depth with a kernel sized from the disk (thesis 3.4, PCSS).
#include "passes/pass_setup.h"

#include "shared.h"

namespace ssgi {

graph::ImageRef addShadowPass(PassSetup& s, const GBufferAndRsm& in, EffectCache* cache) {
    graph::ImageRef shadow = s.graph.createImage(
        "shadow", VK_FORMAT_R16G16B16A16_SFLOAT, s.size,
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    const CacheInputs history = cacheInputs(s, cache, in.gbuffer.viewDepth);

    addKeepPass(s, cache, {shadow});
    using graph::Use;
    ComputePassDesc pass{"shadow", "shadow.comp"};
    pass.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"rsmDepth", in.rsm.depth, Use::Sampled},
                   {"historyViewDepth", history.viewDepth, Use::Sampled},
                   {"historyCount", history.count, Use::Sampled},
                   {"shadowImage", shadow, Use::StorageWrite}};
    pass.pushSize = sizeof(shader::ShadowConstants);
    pass.spec = {{int(s.model.settings.shadow_taps)}};
    addComputePass(s, std::move(pass), [&s, cache](const ComputeRecorder& r) {
        shader::ShadowConstants constants{};
        constants.rotation = s.patternRotation;
        constants.scale = s.patternScale;
        constants.normalOffset = float(s.model.settings.shadow_bias);
        constants.radialOffset = radialOffset(s, cache);
        constants.cache = cacheConstants(s, cache);
        const VkExtent2D area = cacheDispatch(s, cache, s.size);
        r.dispatch(area.width, area.height, constants);
    });
    return shadow;
}

} // namespace ssgi
