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
    const vk::Pipeline gather =
        s.computePipeline("indirect.comp", 7, 1, sizeof(shader::IndirectConstants), spec);
    const vk::Pipeline upsample =
        s.computePipeline("upsample.comp", 8, 1, sizeof(shader::IndirectConstants), spec);

    const CacheInputs history = cacheInputs(s, cache, in.gbuffer.position);
    auto constants = [&s, halfSize, cache]() {
        shader::IndirectConstants c{};
        c.rotation = s.patternRotation;
        c.scale = s.patternScale;
        c.radius = float(s.model.settings.indirect_radius);
        c.radialOffset = radialOffset(s, cache);
        c.width = int(halfSize.width);
        c.height = int(halfSize.height);
        c.cache = cacheConstants(s, cache);
        return c;
    };
    auto sceneInputs = [&s, in, history](const graph::PassContext& pc, vk::Descriptors& d) {
        d.uniformBuffer(0, s.frameUniforms.buffer, s.frameUniforms.size)
            .sampledImage(1, pc.image(in.gbuffer.position).view, s.nearestSampler)
            .sampledImage(2, pc.image(in.gbuffer.normal).view, s.nearestSampler)
            .sampledImage(3, pc.image(in.rsm.position).view, s.nearestSampler)
            .sampledImage(4, pc.image(in.rsm.normal).view, s.nearestSampler)
            .sampledImage(5, pc.image(in.rsm.third).view, s.nearestSampler)
            .sampledImage(6, pc.image(history.position).view, s.nearestSampler)
            .sampledImage(7, pc.image(history.count).view, s.nearestSampler);
    };

    addKeepPass(s, cache, {half, full});
    using graph::Use;
    const std::vector<graph::ImageUse> reads = {
        {in.gbuffer.position, Use::Sampled}, {in.gbuffer.normal, Use::Sampled},
        {in.rsm.position, Use::Sampled},     {in.rsm.normal, Use::Sampled},
        {in.rsm.third, Use::Sampled},        {history.position, Use::Sampled},
        {history.count, Use::Sampled}};
    std::vector<graph::ImageUse> gatherUses = reads;
    gatherUses.push_back({half, Use::StorageWrite});
    s.graph.addPass(
        "indirect", graph::PassKind::Compute, gatherUses,
        [&s, cache, half, gather, constants, sceneInputs](const graph::PassContext& pc) {
            vk::Descriptors d;
            sceneInputs(pc, d);
            d.storageImage(8, pc.image(half).view).push(s.ctx, pc.cmd, gather);
            const VkExtent2D area = cacheDispatch(s, cache, s.size, 2);
            vk::dispatch(pc.cmd, gather, area.width, area.height, constants());
        },
        [halfRes] { return halfRes; }); // at full resolution, upsample gathers every pixel

    std::vector<graph::ImageUse> upsampleUses = reads;
    upsampleUses.push_back({half, Use::Sampled});
    upsampleUses.push_back({full, Use::StorageWrite});
    s.graph.addPass(
        "upsample", graph::PassKind::Compute, upsampleUses,
        [&s, cache, half, full, upsample, constants, sceneInputs](const graph::PassContext& pc) {
            vk::Descriptors d;
            sceneInputs(pc, d);
            d.sampledImage(8, pc.image(half).view, s.nearestSampler)
                .storageImage(9, pc.image(full).view)
                .push(s.ctx, pc.cmd, upsample);
            const VkExtent2D area = cacheDispatch(s, cache, s.size);
            vk::dispatch(pc.cmd, upsample, area.width, area.height, constants());
        });
    return full;
}

} // namespace ssgi
