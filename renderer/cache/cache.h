// The temporal cache (thesis 3.1) as data and pure functions, below the passes: each cached
// effect's history (its value with the resampling blur it carries, and a rotation count per
// pixel, as ping-pong pairs in the frame graph), its tiled refresh (tile_refresh.h), the constants
// its passes read, and what restarts or carries a history (invalidation.cpp): a moved light or
// object (restartCache), a resize (carryCaches). The world positions every history was computed
// at are last frame's G-buffer's, whose view depths are one pair all effects share
// (CacheSet::viewDepthHistory). The passes that keep, blend and read a history are in
// passes/cached_effect_pass.h; camera cuts restart the whole graph's histories
// (Renderer::renderFrame).
#pragma once

#include "cache/tile_refresh.h"
#include "frame_state.h"
#include "graph/frame_graph.h"
#include "scene/settings.h"
#include "shared.h"

#include <deque>
#include <memory>
#include <optional>
#include <string>

namespace ssgi {

// What an effect is, as far as its cache is concerned; declared once where the frame adds the
// effect (frame.cpp). Its cache's settings are the rows cache_<name>, cache_tile_<name> and
// cache_blur_<name> of the settings table.
struct CachedEffect {
    std::string name;            // its images ("<name>.history", "<name>.count") and passes
    bool lightDependent = false; // a moved light restarts its history
    // A scalar effect (the shadow, the AO): its history holds value and blur in two half floats
    // (RG16F) rather than an RGB value and its blur (RGBA16F).
    bool scalar = false;
    // What an object that moved restarts (shared_cache.h MOTION_*): the whole history; per pixel,
    // those within `motionReach` of it, or those whose path to the light passes near it.
    int motionTest = MOTION_RESTART_ALL;
    float motionReach = 0.0f; // scene units
    // An effect computed without noise (no turning pattern: the sky's visibility): one
    // computation is converged (its rotations are 1), and a value computed again replaces its
    // history rather than being blended into it.
    bool exact = false;
    // Its value does not depend on the view (the shadow of a still light, the sky's visibility
    // from world-space maps): where the history's texels around a reprojected point agree,
    // resampling them blurs nothing, and the value is kept while the camera moves
    // (temporal.comp historyAt). A screen-space effect's agreeing value was right for the view
    // that computed it, not necessarily for this one.
    bool viewIndependent = false;
};

// The temporal cache of one effect: its declaration, its history as two ping-pong pairs
// (frame-graph history ids), its tiled refresh and the resampling blur it may carry.
struct EffectCache {
    CachedEffect effect;
    uint32_t slot = 0;         // its place in CacheSet::effects and FrameState::effects
    uint32_t valueHistory = 0; // value and blur
    uint32_t countHistory = 0; // rotation count, and whether it is due (kCountFormat)
    std::unique_ptr<TileRefresh> refresh;
    float blurBudget = 0.0f; // squared pixels (cache_blur_<name>)
    const std::string& name() const { return effect.name; }
};

// A cache's count texel: the rotations accumulated at a pixel (0: it holds nothing; a blend's
// effective number of samples where the blur budget cut the history's weight), and whether the
// temporal pass asked for it to be computed next frame (reuse while moving). One byte, the
// count in half steps to CACHE_COUNT_HALVES and whole ones to CACHE_COUNT_MAX with `due` in its
// top bit (shared_cache.h countCode; temporal.glsl packCount, unpackCount).
constexpr VkFormat kCountFormat = VK_FORMAT_R8_UNORM;
struct CountTexel {
    float count = 0.0f;
    bool due = false;
};
uint8_t packCount(CountTexel t);
CountTexel unpackCount(uint8_t code);

// A scalar effect's value of the frame (CachedEffect::scalar): one half float, never negative
// where computed, kScalarSkipped (temporal.glsl SCALAR_SKIPPED) where the effect skipped the
// pixel; any other effect's value is RGBA16F, its alpha 0 (SKIPPED) where skipped.
constexpr VkFormat kScalarValueFormat = VK_FORMAT_R16_SFLOAT;
constexpr float kScalarSkipped = -1.0f;

// An effect whose value of this frame is made (`value`) and not yet blended into its history:
// the frame's next temporal pass carries it (temporal_pass.cpp).
struct WaitingEffect {
    const EffectCache* cache;
    graph::ImageRef value;
};

// Every cached effect of a frame, and the history of the G-buffer's view depths they share.
struct CacheSet {
    std::deque<EffectCache> effects; // a deque: passes keep pointers to its elements
    std::optional<uint32_t> viewDepthHistory;
    graph::ImageRef reprojection; // this frame's, shared by every effect (reprojection_pass.cpp)
    std::vector<WaitingEffect> waiting; // in the order the frame made them
    uint32_t temporalPasses = 0;        // the temporal dispatches the frame has so far
};

// Whether the settings cache the effect `name`: cache and cache_<name> on.
bool effectCached(const Settings& settings, const std::string& name);
// Of an effect's `count` samples of one kind (directions, steps along them, taps), those a
// frame takes: all of them where the effect is computed anew every frame, where its cache's
// history restarts this frame (`restart`: the first frame, a cut, a moved light for an effect
// of the light), which has no frames before it, or where a moving camera cuts its history's
// weight (a blur budget of 0, cache_blur_<name>: the shadow's and SSDO's by default); where its
// cache accumulates frames, the share cache_samples of them (at least one), the frames before
// supplying the rest (docs/temporal-cache.md, "Samples a frame").
int samplesPerFrame(const Settings& settings, const std::string& name, int count, bool restart);

// The temporal cache of `effect` when the settings cache it (effectCached), made in `graph` at
// `size`; nullptr otherwise.
EffectCache* createCache(graph::FrameGraph& graph, CacheSet& caches, const Settings& settings,
                         VkExtent2D size, const CachedEffect& effect);

// This frame's part of each cache (FrameState::effects): whether its history holds last frame,
// and, while it does, the next tile of its tiled refresh.
std::vector<CachedEffectFrame> nextCacheFrames(const graph::FrameGraph& graph, CacheSet& caches);

// The constants an effect's passes read of its cache this frame (temporal.glsl); all zero
// without a cache (no history, nothing converges).
shader::CacheConstants cacheConstants(const Settings& settings, const EffectCache* cache,
                                      const FrameState& frame);
// The reprojection test as the settings give it (cache_epsilon, cache_thin_geometry): what the
// reprojection pass takes.
shader::ReprojectionConstants reprojectionConstants(const Settings& settings, bool historyValid);
// The pattern's radial offset for an effect's pass (the constants' pattern.w): this frame's
// FrameState::patternOffset when the effect is cached, else -1 (a single frame's fixed pattern).
float radialOffset(const EffectCache* cache, const FrameState& frame);
// The threads a cached effect's pass dispatches: the whole image (`full`), or none on a settled
// frame, which computes nothing (Renderer::decideFrame).
VkExtent2D cacheDispatch(const EffectCache* cache, const FrameState& frame, VkExtent2D full);

// A moved light or object: the cache's history (value and count) holds nothing from the next
// frame on.
void restartCache(graph::FrameGraph& graph, const EffectCache& cache);

// A resize: every history of `from` (a frame of another size, `fromSize`, the same scene and
// settings) that `to` also has is handed over for `to`'s next frame, which reprojects it at its
// old size; its counts are lowered to one sample. With no cache, nothing.
void carryCaches(graph::FrameGraph& from, const CacheSet& fromCaches, VkExtent2D fromSize,
                 graph::FrameGraph& to, const CacheSet& toCaches);

} // namespace ssgi
