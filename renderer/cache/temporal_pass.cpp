// <effect>.temporal: the temporal cache of one effect (thesis 3.1): reverse reprojection,
// accumulation with the thesis's confidence rule or a running mean, reuse of converged pixels
// (the effect pass skips them), tiled refresh. The history pair swaps each frame in the graph.
#include "cache/cache.h"
#include "passes/pass_setup.h"

#include <algorithm>

namespace ssgi {

EffectCache* createCache(PassSetup& s, const std::string& name, const EffectCacheSettings& settings,
                         EffectKind kind) {
    if (!s.model.settings.cache || !settings.cached) return nullptr;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    EffectCache& c = s.caches.emplace_back();
    c.name = name;
    c.scalar = kind.scalar;
    c.value = s.graph.createHistory(
        name + ".history", c.scalar ? VK_FORMAT_R16G16_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT,
        s.size, usage);
    // Counts are whole numbers up to cache_rotations, or a blend's effective number of samples:
    // a half float holds them to 1/1000 of their value.
    c.count = s.graph.createHistory(name + ".count", VK_FORMAT_R16_SFLOAT, s.size, usage);
    if (s.model.settings.cache_refresh)
        c.refresh = std::make_unique<TileRefresh>(
            s.size.width, s.size.height, uint32_t(settings.tileSize), uint32_t(s.caches.size()));
    c.lightDependent = kind.lightDependent;
    c.blurBudget = float(settings.blurBudget);
    return &c;
}

CacheInputs cacheInputs(const PassSetup& s, const EffectCache* cache, graph::ImageRef fallback) {
    using graph::FrameGraph;
    if (!cache) return {fallback, fallback};
    return {FrameGraph::previous(*s.viewDepthHistory), FrameGraph::previous(cache->count)};
}

shader::CacheConstants cacheConstants(const PassSetup& s, const EffectCache* cache) {
    shader::CacheConstants c{};
    if (!cache) return c; // historyValid 0: no history, nothing converges
    c.historyValid = s.graph.hasHistory(cache->value) ? 1 : 0;
    c.rotations = int(s.model.settings.cache_rotations);
    c.refreshTile = cache->refreshTile;
    c.tileSize = cache->refresh ? int(cache->refresh->tileSize()) : 1;
    c.confidenceBias = float(s.model.settings.cache_bias);
    c.epsilon = float(s.model.settings.cache_epsilon);
    c.runningMean = s.model.settings.cache_method != 0 ? 1 : 0;
    c.settled = s.settled ? 1 : 0;
    c.motionTest = cache->motionTest;
    c.motionReach = cache->motionReach;
    c.blurBudget = cache->blurBudget;
    c.reprojection = (s.model.settings.cache_thin_geometry ? REPROJECT_THIN_GEOMETRY : 0) |
                     (s.model.settings.cache_screen_edge ? REPROJECT_SCREEN_EDGE : 0);
    return c;
}

float radialOffset(const PassSetup& s, const EffectCache* cache) {
    return cache ? s.patternOffset : -1.0f;
}

VkExtent2D cacheDispatch(const PassSetup& s, const EffectCache* cache, VkExtent2D full,
                         uint32_t divisor) {
    if (!cache || !s.settled) return full;
    if (!cache->refresh || cache->refreshTile < 0) return {0, 0};
    const TileRect tile = cache->refresh->rect(uint32_t(cache->refreshTile));
    return {(tile.width + divisor - 1) / divisor, (tile.height + divisor - 1) / divisor};
}

void addKeepPass(PassSetup& s, EffectCache* cache, std::vector<graph::ImageRef> outputs) {
    if (!cache) return;
    using graph::FrameGraph;
    using graph::Use;
    std::vector<graph::ImageUse> uses = {{FrameGraph::previous(cache->value), Use::TransferSrc},
                                         {FrameGraph::previous(cache->count), Use::TransferSrc},
                                         {FrameGraph::current(cache->value), Use::TransferDst},
                                         {FrameGraph::current(cache->count), Use::TransferDst}};
    for (const graph::ImageRef& output : outputs)
        uses.push_back({output, Use::TransferDst});
    s.graph.addPass(
        cache->name + ".keep", graph::PassKind::Transfer, uses,
        [cache, outputs](const graph::PassContext& pc) {
            for (uint32_t history : {cache->value, cache->count}) {
                const vk::Image& from = pc.image(FrameGraph::previous(history));
                const vk::Image& to = pc.image(FrameGraph::current(history));
                VkImageCopy region{};
                region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.dstSubresource = region.srcSubresource;
                region.extent = {from.extent.width, from.extent.height, 1};
                vkCmdCopyImage(pc.cmd, from.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to.image,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
            }
            const VkClearColorValue zero{};
            const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            for (const graph::ImageRef& output : outputs)
                vkCmdClearColorImage(pc.cmd, pc.image(output).image,
                                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
        },
        [&s] { return s.settled; });
}

graph::ImageRef addTemporalPass(PassSetup& s, EffectCache* cache, graph::ImageRef raw,
                                const GBufferAndRsm& in) {
    if (!cache) return raw;
    using graph::FrameGraph;
    using graph::Use;
    const graph::ImageRef value = FrameGraph::current(cache->value);
    const CacheInputs history = cacheInputs(s, cache, in.gbuffer.viewDepth);
    ComputePassDesc pass{cache->name + ".temporal", "temporal.comp"};
    pass.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"current", raw, Use::Sampled},
                   {"historyValue", FrameGraph::previous(cache->value), Use::Sampled},
                   {"historyViewDepth", history.viewDepth, Use::Sampled},
                   {"historyCount", history.count, Use::Sampled},
                   {"newValue", value, Use::StorageWrite},
                   {"newCount", FrameGraph::current(cache->count), Use::StorageWrite}};
    pass.pushSize = sizeof(shader::TemporalConstants);
    pass.spec = {{cache->scalar ? 1 : 0}};
    addComputePass(s, std::move(pass), [&s, cache](const ComputeRecorder& r) {
        shader::TemporalConstants constants{cacheConstants(s, cache)};
        const VkExtent2D area = cacheDispatch(s, cache, s.size);
        r.dispatch(area.width, area.height, constants);
    });
    return value;
}

} // namespace ssgi
