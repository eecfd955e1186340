// indirect + upsample: one-bounce indirect light from the RSM's virtual point lights, gathered
// at half resolution and brought to full resolution from geometry-compatible neighbours; the
// pixels without one are gathered at full resolution (thesis 3.3 and ch. 4).
#include "passes/pass_setup.h"

#include "shared.h"

namespace ssgi {

graph::ImageRef addIndirectPasses(PassSetup& s, const GBufferAndRsm& in, EffectCache* cache) {
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const VkExtent2D halfSize{(s.size.width + 1) / 2, (s.size.height + 1) / 2};
    graph::ImageRef half =
        s.graph.createImage("indirect.half", VK_FORMAT_R16G16B16A16_SFLOAT, halfSize, usage);
    graph::ImageRef full =
        s.graph.createImage("indirect", VK_FORMAT_R16G16B16A16_SFLOAT, s.size, usage);
    const vk::Specialization spec{
        {int(s.model.settings.indirect_vpls), int(s.model.settings.indirect_visibility),
         int(s.model.settings.indirect_visibility_steps), int(s.model.settings.indirect_half_res)}};
    const bool halfRes = s.model.settings.indirect_half_res;
    const CacheInputs history = cacheInputs(s, cache, in.gbuffer.viewDepth);
    auto constants = [&s, halfSize, cache]() { return indirectConstants(s, cache, halfSize); };

    addKeepPass(s, cache, {half, full});
    using graph::Use;
    const std::vector<ShaderImage> reads = {
        {"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
        {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
        {"rsmVpls", in.rsm.vpls, Use::Sampled},
        {"historyViewDepth", history.viewDepth, Use::Sampled},
        {"historyCount", history.count, Use::Sampled}};
    ComputePassDesc gather{"indirect", "indirect.comp", reads};
    gather.images.push_back({"halfIndirect", half, Use::StorageWrite});
    gather.pushSize = sizeof(shader::IndirectConstants);
    gather.spec = spec;
    addComputePass(
        s, std::move(gather),
        [&s, cache, constants](const ComputeRecorder& r) {
            const VkExtent2D area = cacheDispatch(s, cache, s.size, 2);
            r.dispatch(area.width, area.height, constants());
        },
        [halfRes] { return halfRes; }); // at full resolution, upsample gathers every pixel

    ComputePassDesc upsample{"upsample", "upsample.comp", reads};
    upsample.images.push_back({"halfIndirect", half, Use::Sampled});
    upsample.images.push_back({"indirectImage", full, Use::StorageWrite});
    upsample.pushSize = sizeof(shader::IndirectConstants);
    upsample.spec = spec;
    addComputePass(s, std::move(upsample), [&s, cache, constants](const ComputeRecorder& r) {
        const VkExtent2D area = cacheDispatch(s, cache, s.size);
        r.dispatch(area.width, area.height, constants());
    });
    return full;
}

} // namespace ssgi
