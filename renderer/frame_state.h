// What one frame does and why: computed once by the Renderer before the frame is recorded
// (Renderer::decideFrame) and handed by the frame graph to every pass's enable and record
// callback. Nothing else a pass reads changes from frame to frame.
#pragma once

#include <cstdint>
#include <vector>

namespace ssgi {

// One cached effect's part of the frame, in the order FrameBuild::caches holds the effects.
struct CachedEffectFrame {
    bool hasHistory = false; // last frame's value is there to reproject
    int refreshTile = -1;    // the tile its tiled refresh recomputes this frame, or none
};

struct FrameState {
    // The sampling patterns' turn, scale and place in their radial strata this frame (thesis
    // 3.1.2): successive frames take different samples, which the cache accumulates.
    float patternRotation = 0.0f;
    float patternScale = 1.0f;
    float patternOffset = 0.5f;
    // Where the patterns stand (FrameUniforms.patternFrame): the frame's number, for passes that
    // keep something per frame parity (the world cache's counters).
    uint32_t patternFrame = 0;
    // The light changed since the RSM was last drawn (always so without the cache): the RSM and
    // what is made from it alone (the flux's VPL map) are made again.
    bool drawRsm = true;
    // The G-buffer is drawn unless both sides of its view-depth pair already hold this frame's
    // view, drawn by this renderer in the last two frames with the camera and every object where
    // they are now (its other images then hold the view too). Always drawn without the cache.
    bool drawGBuffer = true;
    // An object moved since the sky maps were drawn (or they never were).
    bool drawSkyMaps = true;
    // The world cache of indirect_method 3 (world_cache_pass.cpp): the light moved since the
    // last frame (every cell restarts); an object moved since the last frame (the cells near it
    // restart); an object moved since the voxel grid was drawn, or it never was; the table holds
    // nothing yet, or the cache is off (it is cleared before the frame fills it).
    bool lightMoved = false;
    bool objectsMoved = false;
    bool drawVoxels = true;
    bool clearWorldCache = true;
    // Camera, light and objects unchanged for as many frames as a pixel needs rotations: every
    // pixel is converged, and the cached effects compute nothing (no refresh tile: a refreshed
    // pixel's new sample would be left out of its converged history, temporal.comp).
    bool settled = false;
    // The first settled frame: the keep passes copy each history whole to this frame's side of
    // its pair. From then on both sides hold it, and settled frames write neither.
    bool copyHistories = false;
    // What the composite shows: the view's place in kViews (passes/views.h).
    int view = 0;
    std::vector<CachedEffectFrame> effects;
};

} // namespace ssgi
