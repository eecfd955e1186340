// The passes of a cached effect (thesis 3.1) around the effect's own: <effect>.keep carries the
// history over on the first settled frame (settled frames compute nothing), and the frame's
// temporal pass, one for every cached effect, blends this frame's value into the history. An
// effect of one compute pass is declared whole by addCachedComputePass; an effect of several
// passes (the indirect light) uses the pieces below it. docs/frame.md, "Adding a cached effect".
#pragma once

#include "cache/cache.h"
#include "passes/compute_pass.h"
#include "passes/frame_build.h"
#include "passes/scene_pass.h"

#include <functional>
#include <string>
#include <vector>

namespace ssgi {

// What a cached effect's record function gets: this frame's state and its cache's part of it.
class CachedRecorder {
public:
    CachedRecorder(const FrameBuild& build, const EffectCache* cache, const ComputeRecorder& r)
        : build_(build), cache_(cache), recorder_(r) {}
    const FrameState& frame() const { return recorder_.frame(); }
    // The sampling pattern's radial place: this frame's when cached, else -1 (a fixed pattern).
    float radialOffset() const { return ssgi::radialOffset(cache_, frame()); }
    // Sets `constants.cache` and dispatches the pixels the cache leaves to compute this frame,
    // by the pass's restart variant where the history restarts (CachedComputePass::restartSpec).
    template <typename T> void dispatch(T constants) const {
        constants.cache = cacheConstants(build_.settings, cache_, frame());
        const VkExtent2D area = cacheDispatch(cache_, frame(), build_.size);
        if (historyRestarts())
            recorder_.restarting().dispatch(area.width, area.height, constants);
        else
            recorder_.dispatch(area.width, area.height, constants);
    }
    // Whether the effect's cache holds nothing of last frame (or there is no cache).
    bool historyRestarts() const { return !cache_ || !frame().effects[cache_->slot].hasHistory; }

private:
    const FrameBuild& build_;
    const EffectCache* cache_;
    const ComputeRecorder& recorder_;
};

// A cached effect computed by one compute shader at full resolution. Its shader binds, in this
// order: `inputs`, then "historyViewDepth", "reprojection" and "historyCount" (last frame's
// G-buffer view depths, this frame's reprojection and the effect's rotation counts, to skip
// converged pixels; temporal.glsl), then "historyValue" where `bindsHistory` (last frame's
// blended values, to check a value it would reuse), then
// "<name>Image", the RGBA16F image it writes (named <name> in the graph); then `uniforms`.
// With a `term` (a term's view in views.h), what it returns is also handed to the composite as
// that lighting term.
struct CachedComputePass {
    CachedEffect effect;
    std::string term;
    std::string shader;
    std::vector<ShaderImage> inputs;
    std::vector<ShaderBuffer> uniforms;
    uint32_t pushSize = 0;
    bool bindsHistory = false;
    vk::Specialization spec;
    // Its variant for a frame where the history restarts and every pixel is computed anew: the
    // first frame, a cut, a moved light for an effect of the light (all of its samples, where
    // `spec` takes the share cache_samples of them).
    std::optional<vk::Specialization> restartSpec;
};
using CachedRecordFn = std::function<void(const CachedRecorder&)>;

// The effect's cache (when the settings cache it), its keep pass and its compute pass, its value
// handed to the temporal pass; returns what the effect's consumers read once that pass has run
// (the blended history, or the raw value without a cache), which is also the composite's term
// when the pass names one.
graph::ImageRef addCachedComputePass(FrameBuild& build, const GBuffer& gbuffer,
                                     CachedComputePass pass, CachedRecordFn record);

// The pieces, for an effect of several passes.
// Its "historyViewDepth", "reprojection" and "historyCount" bindings: last frame's G-buffer view
// depths, this frame's reprojection and the cache's rotation counts, or `fallback` (any image
// the pass reads anyway) without a cache.
std::vector<ShaderImage> cacheBindings(const FrameBuild& build, const EffectCache* cache,
                                       graph::ImageRef fallback);
// <effect>.keep, run on the first settled frame alone, before the effect: last frame's history
// copied whole to this frame's side of the pair (settled frames compute nothing, so from then
// on both sides hold it), and the images in `cleared` cleared to "skipped", so that what the
// effect's passes wrote last reads as skipped while nothing is computed.
void addKeepPass(FrameBuild& build, const EffectCache* cache, std::vector<graph::ImageRef> cleared);
// Hands an effect's value of this frame (`raw`) to the frame's next temporal pass
// (addTemporalPass, temporal_pass.cpp), which blends it into its history; returns what the
// effect's consumers read once that pass has run (the raw value at once when there is no cache).
graph::ImageRef blendInTemporalPass(FrameBuild& build, const EffectCache* cache,
                                    graph::ImageRef raw);

// temporal: blends every effect handed to it since the last (blendInTemporalPass) into its
// history, TEMPORAL_EFFECT_SLOTS (or cache_temporal_slots) effects a dispatch. The frame adds it
// after the effects' passes and before what reads their blended values; nothing without a cache.
void addTemporalPass(FrameBuild& build, const GBuffer& gbuffer);

} // namespace ssgi
