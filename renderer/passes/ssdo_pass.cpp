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
    const double radius = s.model.settings.ssdo_radius;
    const float rMax = radius > 0.0 ? float(radius) : aoRadius(s.model);
    const CacheInputs history = cacheInputs(s, cache, in.gbuffer.viewDepth);

    addKeepPass(s, cache, {ssdo});
    using graph::Use;
    ComputePassDesc pass{"ssdo", "ssdo.comp"};
    // Without peeling the shader never reads its second layer: any valid image will do.
    pass.images = {
        {"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
        {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
        {"gbufferAlbedo", in.gbuffer.albedo, Use::Sampled},
        {"directRadiance", direct, Use::Sampled},
        {"historyViewDepth", history.viewDepth, Use::Sampled},
        {"historyCount", history.count, Use::Sampled},
        {"secondLayer", secondLayer.valid() ? secondLayer : in.gbuffer.viewDepth, Use::Sampled},
        {"ssdoImage", ssdo, Use::StorageWrite}};
    pass.pushSize = sizeof(shader::SsdoConstants);
    pass.spec = {{int(s.model.settings.ssdo_samples), secondLayer.valid() ? 1 : 0}};
    addComputePass(s, std::move(pass), [&s, cache, rMax](const ComputeRecorder& r) {
        shader::SsdoConstants constants{};
        constants.rotation = s.patternRotation;
        constants.scale = s.patternScale;
        constants.rMax = rMax;
        constants.bounceStrength = float(s.model.settings.ssdo_bounce);
        constants.cache = cacheConstants(s, cache);
        const VkExtent2D area = cacheDispatch(s, cache, s.size);
        r.dispatch(area.width, area.height, constants);
    });
    return ssdo;
}

} // namespace ssgi
