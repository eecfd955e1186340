// <effect>.keep and the effect's place in the temporal pass: the temporal cache of one effect
// (thesis 3.1) around the effect's own passes: reverse reprojection, accumulation with the
// thesis's confidence rule or a running mean (temporal_pass.cpp), reuse of converged pixels (the
// effect's passes skip them), tiled refresh. The history pair swaps each frame in the graph.
#include "passes/cached_effect_pass.h"

namespace ssgi {

std::vector<ShaderImage> cacheBindings(const FrameBuild& build, const EffectCache* cache,
                                       graph::ImageRef fallback) {
    using graph::FrameGraph;
    using graph::Use;
    if (!cache)
        return {{"historyViewDepth", fallback, Use::Sampled},
                {"reprojection", build.caches.reprojection, Use::Sampled},
                {"historyCount", fallback, Use::Sampled}};
    return {
        {"historyViewDepth", FrameGraph::previous(*build.caches.viewDepthHistory), Use::Sampled},
        {"reprojection", build.caches.reprojection, Use::Sampled},
        {"historyCount", FrameGraph::previous(cache->countHistory), Use::Sampled}};
}

void addKeepPass(FrameBuild& build, const EffectCache* cache,
                 std::vector<graph::ImageRef> cleared) {
    if (!cache) return;
    using graph::FrameGraph;
    using graph::Use;
    const uint32_t histories[] = {cache->valueHistory, cache->countHistory};
    std::vector<graph::ImageUse> uses;
    for (uint32_t history : histories) {
        uses.push_back({FrameGraph::previous(history), Use::TransferSrc});
        uses.push_back({FrameGraph::current(history), Use::TransferDst});
    }
    for (const graph::ImageRef& image : cleared)
        uses.push_back({image, Use::TransferDst});
    build.graph.addPass(
        cache->name() + ".keep", graph::PassKind::Transfer, uses,
        [histories = std::vector<uint32_t>(std::begin(histories), std::end(histories)),
         cleared](const graph::PassContext& pc) {
            for (uint32_t history : histories) {
                const vk::Image& from = pc.image(FrameGraph::previous(history));
                const vk::Image& to = pc.image(FrameGraph::current(history));
                VkImageCopy region{};
                region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.dstSubresource = region.srcSubresource;
                region.extent = {from.extent.width, from.extent.height, 1};
                vkCmdCopyImage(pc.cmd, from.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to.image,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
            }
            for (const graph::ImageRef& image : cleared) {
                const vk::Image& cleared = pc.image(image);
                if (cleared.format == kScalarValueFormat) // SCALAR_SKIPPED
                    vk::clearTo(pc.cmd, cleared.image, kScalarSkipped);
                else
                    vk::clearToZero(pc.cmd, cleared.image); // SKIPPED
            }
        },
        // Only the first settled frame: after it no pass writes the pair's sides or the cleared
        // images while the frame stays settled (on a GPU, copying and clearing every settled
        // frame cost more than the rest of the frame).
        [](const FrameState& frame) { return frame.copyHistories; });
}

graph::ImageRef blendInTemporalPass(FrameBuild& build, const EffectCache* cache,
                                    graph::ImageRef raw) {
    if (!cache) return raw;
    build.caches.waiting.push_back({cache, raw});
    return graph::FrameGraph::current(cache->valueHistory);
}

graph::ImageRef addCachedComputePass(FrameBuild& build, const GBuffer& gbuffer,
                                     CachedComputePass desc, CachedRecordFn record) {
    const std::string& name = desc.effect.name;
    const EffectCache* cache =
        createCache(build.graph, build.caches, build.settings, build.size, desc.effect);
    // A scalar effect's value is one half float, SCALAR_SKIPPED where skipped (temporal.glsl
    // effectValue); any other's RGB and whether it was computed.
    const graph::ImageRef raw = build.graph.createImage(
        name, desc.effect.scalar ? kScalarValueFormat : VK_FORMAT_R16G16B16A16_SFLOAT, build.size,
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    // On settled frames the effect's image reads "skipped" (what the tests and
    // bench/computed_pixels.py count as computed).
    addKeepPass(build, cache, {raw});
    ComputePassDesc pass{name, desc.shader, std::move(desc.inputs)};
    for (ShaderImage& history : cacheBindings(build, cache, gbuffer.viewDepth))
        pass.images.push_back(std::move(history));
    if (desc.bindsHistory)
        pass.images.push_back(
            {"historyValue",
             cache ? graph::FrameGraph::previous(cache->valueHistory) : gbuffer.viewDepth,
             graph::Use::Sampled});
    pass.images.push_back({name + "Image", raw, graph::Use::StorageWrite});
    pass.uniforms = std::move(desc.uniforms);
    pass.pushSize = desc.pushSize;
    pass.spec = std::move(desc.spec);
    pass.restartSpec = std::move(desc.restartSpec);
    addComputePass(build, std::move(pass),
                   [&build, cache, record = std::move(record)](const ComputeRecorder& r) {
                       record(CachedRecorder(build, cache, r));
                   });
    const graph::ImageRef value = blendInTemporalPass(build, cache, raw);
    if (!desc.term.empty()) build.addCompositeTerm(desc.term, value);
    return value;
}

} // namespace ssgi
