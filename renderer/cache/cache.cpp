// The temporal cache's data: making an effect's history, this frame's part of each cache, the
// constants its passes read, and what restarts or carries a history.
#include "cache/cache.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace ssgi {

uint8_t packCount(CountTexel t) {
    return uint8_t(shader::countCode(t.count, t.due));
}

CountTexel unpackCount(uint8_t code) {
    return {shader::countOfCode(float(code)), shader::dueOfCode(float(code))};
}

bool effectCached(const Settings& settings, const std::string& name) {
    return settings.cache && settingValue(settings, "cache_" + name) != 0.0;
}

int samplesPerFrame(const Settings& settings, const std::string& name, int count, bool restart) {
    // An effect without a blur budget (cache_blur_<name> 0) cuts its history's weight wherever
    // a moving camera resamples it, so that a moving frame holds that frame's samples alone.
    const bool keptWhileMoving = settingValue(settings, "cache_blur_" + name) > 0.0;
    if (restart || !effectCached(settings, name) || !keptWhileMoving) return count;
    return std::max(1, int(std::lround(double(count) * settings.cache_samples)));
}

EffectCache* createCache(graph::FrameGraph& graph, CacheSet& caches, const Settings& settings,
                         VkExtent2D size, const CachedEffect& effect) {
    const std::string& name = effect.name;
    if (!effectCached(settings, name)) return nullptr;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    EffectCache& c = caches.effects.emplace_back();
    c.effect = effect;
    c.slot = uint32_t(caches.effects.size() - 1);
    c.valueHistory = graph.createHistory(
        name + ".history", effect.scalar ? VK_FORMAT_R16G16_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT,
        size, usage);
    // Counts are whole numbers up to cache_rotations, half a sample, or a blend's effective
    // number of samples: one byte holds them to half a sample, and whether the pixel is due
    // (shared_cache.h countCode).
    c.countHistory = graph.createHistory(name + ".count", kCountFormat, size, usage);
    // Each effect its own order of tiles, from its name: the same whatever the frame adds
    // before it.
    uint32_t seed = 2166136261u; // FNV-1a
    for (char ch : name)
        seed = (seed ^ uint8_t(ch)) * 16777619u;
    if (settings.cache_refresh)
        c.refresh = std::make_unique<TileRefresh>(
            size.width, size.height, uint32_t(settingValue(settings, "cache_tile_" + name)), seed);
    c.blurBudget = float(settingValue(settings, "cache_blur_" + name));
    return &c;
}

std::vector<CachedEffectFrame> nextCacheFrames(const graph::FrameGraph& graph, CacheSet& caches) {
    std::vector<CachedEffectFrame> frames;
    for (EffectCache& cache : caches.effects) {
        CachedEffectFrame& f = frames.emplace_back();
        f.hasHistory = graph.hasHistory(cache.valueHistory);
        f.refreshTile = cache.refresh && f.hasHistory ? int(cache.refresh->next()) : -1;
    }
    return frames;
}

shader::CacheConstants cacheConstants(const Settings& settings, const EffectCache* cache,
                                      const FrameState& frame) {
    shader::CacheConstants c{};
    if (!cache) return c; // historyValid 0: no history, nothing converges
    const CachedEffectFrame& now = frame.effects[cache->slot];
    c.historyValid = now.hasHistory ? 1 : 0;
    c.rotations = cache->effect.exact ? 1 : int(settings.cache_rotations);
    c.refreshTileCorner = -1;
    if (cache->refresh && now.refreshTile >= 0) {
        const TileRect tile = cache->refresh->rect(uint32_t(now.refreshTile));
        c.refreshTileCorner = int(tile.x) + REFRESH_TILE_ROW * int(tile.y);
    }
    c.tileSize = cache->refresh ? int(cache->refresh->tileSize()) : 1;
    c.confidenceBias = float(settings.cache_bias);
    c.runningMean = settings.cache_method != 0 ? 1 : 0;
    c.motionTest = cache->effect.motionTest;
    c.motionReach = cache->effect.motionReach;
    c.blurBudget = cache->blurBudget;
    c.reprojection = (settings.cache_screen_edge ? REPROJECT_SCREEN_EDGE : 0) |
                     (settings.cache_reuse_moving ? REUSE_WHILE_MOVING : 0) |
                     (cache->effect.viewIndependent ? REUSE_AGREEING : 0);
    return c;
}

shader::ReprojectionConstants reprojectionConstants(const Settings& settings, bool historyValid) {
    return {float(settings.cache_epsilon), settings.cache_thin_geometry ? 1 : 0,
            historyValid ? 1 : 0};
}

float radialOffset(const EffectCache* cache, const FrameState& frame) {
    return cache ? frame.patternOffset : -1.0f;
}

VkExtent2D cacheDispatch(const EffectCache* cache, const FrameState& frame, VkExtent2D full) {
    return cache && frame.settled ? VkExtent2D{0, 0} : full;
}

void restartCache(graph::FrameGraph& graph, const EffectCache& cache) {
    graph.resetHistory(cache.valueHistory);
    graph.resetHistory(cache.countHistory);
}

void carryCaches(graph::FrameGraph& from, const CacheSet& fromCaches, VkExtent2D fromSize,
                 graph::FrameGraph& to, const CacheSet& toCaches) {
    if (!fromCaches.viewDepthHistory || !toCaches.viewDepthHistory) return;
    // After its last frame every pair of `from` has swapped: what it wrote is the previous side.
    using graph::FrameGraph;
    auto last = [&from](uint32_t history) {
        return from.readTexels(FrameGraph::previous(history));
    };
    bool carried = false;
    for (const EffectCache& old : fromCaches.effects) {
        if (!from.hasHistory(old.valueHistory)) continue;
        for (const EffectCache& cache : toCaches.effects) {
            if (cache.name() != old.name()) continue;
            to.carryHistory(cache.valueHistory, fromSize, last(old.valueHistory));
            // Each pixel's history counts as half a sample (rotation count 0.5): screen-space
            // effects converge to another value at another size (their samples snap to other
            // pixels), and a history converged at the old size would hold the new one off for
            // dozens of frames (docs/temporal-cache.md, "Resize"). The shadow, which allows no
            // blur, starts over; the others blend the new frames into the resampled image, the
            // first with two thirds of the weight.
            std::vector<uint8_t> count = last(old.countHistory);
            for (uint8_t& code : count) {
                // The first frame at the new size computes what its cache lacks: none is due.
                const CountTexel t = unpackCount(code);
                code = packCount({std::min(t.count, 0.5f), false});
            }
            to.carryHistory(cache.countHistory, fromSize, count);
            carried = true;
        }
    }
    if (carried)
        to.carryHistory(*toCaches.viewDepthHistory, fromSize, last(*fromCaches.viewDepthHistory));
}

} // namespace ssgi
