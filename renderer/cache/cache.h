// The temporal cache (thesis 3.1) as one module: each cached effect's history (its value with
// the resampling blur it carries, and a rotation count per pixel, as ping-pong pairs in the
// frame graph; the world positions are last frame's G-buffer's, whose view depths are one pair
// every effect shares: PassSetup::viewDepthHistory), what an effect pass binds to skip converged
// pixels, the tiled refresh (tile_refresh.h), the temporal and keep passes (temporal_pass.cpp), and
// what restarts or carries a history (invalidation.cpp): a moved light or object (restartCache), a
// resize (carryCaches). Camera cuts restart the whole graph's histories (Renderer::renderFrame).
#pragma once

#include "cache/tile_refresh.h"
#include "graph/frame_graph.h"
#include "shared.h"

#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace ssgi {

struct PassSetup;
struct GBufferAndRsm;

// The temporal cache of one effect: its history (value + blur, and rotation count) as two
// ping-pong pairs, its tiled refresh, and this frame's state. The world positions its history
// was computed at are the G-buffer's of last frame (from its view depths), shared by every effect
// (PassSetup::viewDepthHistory).
struct EffectCache {
    std::string name;
    uint32_t value = 0, count = 0; // frame-graph history ids
    std::unique_ptr<TileRefresh> refresh;
    int refreshTile = -1;        // this frame's
    bool lightDependent = false; // reset when the light changes
    // A scalar effect (the shadow, the AO): its history holds value and blur in two half
    // floats (RG16F) rather than an RGB value and its blur (RGBA16F).
    bool scalar = false;
    // What an object that moved restarts (shared.h MOTION_*): the whole history; per pixel,
    // those within `motionReach` of it, or those whose path to the light passes near it.
    int motionTest = MOTION_RESTART_ALL;
    float motionReach = 0.0f;
    // The resampling blur (squared pixels) its history may carry under a moving camera.
    float blurBudget = 0.0f;
};

// What the settings say of one effect's cache (cache_<effect>, cache_tile_<effect>,
// cache_blur_<effect>).
struct EffectCacheSettings {
    bool cached;
    int tileSize;      // of its tiled refresh
    double blurBudget; // squared pixels
};
// What an effect is: whether a moved light restarts its cache, and whether its value is one
// number (EffectCache::scalar) or a colour.
struct EffectKind {
    bool lightDependent;
    bool scalar;
};
// The temporal cache of an effect, when caching is on (nullptr otherwise).
EffectCache* createCache(PassSetup& setup, const std::string& name,
                         const EffectCacheSettings& settings, EffectKind kind);
// What an effect pass binds as its "historyViewDepth" and "historyCount" inputs (temporal.glsl):
// last frame's G-buffer view depths (its world positions) and its cache's rotation counts, or
// `fallback` (any image the pass reads anyway) without a cache.
struct CacheInputs {
    graph::ImageRef viewDepth, count;
};
CacheInputs cacheInputs(const PassSetup& setup, const EffectCache* cache, graph::ImageRef fallback);
shader::CacheConstants cacheConstants(const PassSetup& setup, const EffectCache* cache);
// The pattern's radial offset for an effect's pass (the constants' pattern.w): this frame's
// PassSetup::patternOffset when the effect is cached, else -1 (a single frame's fixed pattern).
float radialOffset(const PassSetup& setup, const EffectCache* cache);
// The threads a cached effect's pass dispatches: the whole image (`full`), or once settled only
// its refresh tile (none without one); `divisor` 2 for the half-resolution pass.
VkExtent2D cacheDispatch(const PassSetup& setup, const EffectCache* cache, VkExtent2D full,
                         uint32_t divisor = 1);
// <effect>.keep, run only on settled frames before the effect: last frame's history carried
// over whole to this frame's side (the temporal pass then rewrites the refresh tile), and the
// effect's own images cleared, so that what the tile-only passes do not write reads "skipped".
void addKeepPass(PassSetup& setup, EffectCache* cache, std::vector<graph::ImageRef> outputs);

// <effect>.temporal: blends an effect's value of this frame into its history; returns what
// the effect's consumers read (the raw value when there is no cache).
graph::ImageRef addTemporalPass(PassSetup& setup, EffectCache* cache, graph::ImageRef raw,
                                const GBufferAndRsm& inputs);

// A moved light or object: the cache's history (value and count) holds nothing from the next
// frame on.
void restartCache(graph::FrameGraph& graph, const EffectCache& cache);

// A resize: every history of `from` (another size, the same scene and settings) that `to` also
// has is handed over for `to`'s next frame, which reprojects it at its old size; its counts are
// lowered to one sample. With no cache, nothing.
void carryCaches(PassSetup& from, PassSetup& to);

} // namespace ssgi
