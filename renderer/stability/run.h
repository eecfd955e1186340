// Runs one stability case: the renderer under test along the case's timeline (a still warm-up
// until the cache has converged, the camera/light path, a still hold), a fresh renderer with
// the same settings at the final camera, a converged reference there (running mean, twice the
// samples), the path tracer on request, and the measures of measures.h per frame.
#pragma once

#include "metrics/error_map.h"
#include "reference/cache.h"
#include "renderer.h"
#include "scene/animation.h"
#include "stability/cases.h"
#include "stability/measures.h"

#include <functional>
#include <memory>
#include <set>

namespace ssgi::stability {

struct RunOptions {
    uint32_t width = 160, height = 120;
    uint32_t warmup = 40;     // still frames before the path: past the 36 rotations to converge
    uint32_t hold = 40;       // still frames after the last change
    uint32_t converge = 40;   // frames of the fresh renderer and of the converged reference
    uint32_t stillFrames = 8; // further frames of the fresh renderer: flicker once converged
    uint32_t truthSpp = 0;    // path-traced samples per pixel; 0 = no ground truth
    std::vector<std::pair<std::string, double>> settings; // method settings to override
    std::string repository = SSGI_SOURCE_DIR;
};

struct FrameRecord {
    const char* phase = "";   // warmup, path, hold
    int sinceChange = -1;     // frames since camera, light or size last changed; -1 before
    double flicker = kNaN;    // change from the previous frame (flicker()), all geometry
    double error = kNaN;      // relMSE to the converged image, inside the region
    double errorRest = kNaN;  // ... outside it
    double freshError = kNaN; // the fresh renderer's region error at the same age
    double freshRest = kNaN;  // ... outside the region
    double stale = kNaN;      // staleFraction(), moving-light cases
    double reused = kNaN;     // fraction of geometry pixels whose AO history continued
    size_t nonFinite = 0;     // NaN/Inf values over every image of the frame
};

struct CaseResult {
    Case spec;
    uint32_t width = 0, height = 0; // at the end
    size_t regionPixels = 0, geometryPixels = 0;
    std::vector<FrameRecord> frames;
    double convergedError = kNaN;      // region error over the last 4 frames: where it settles
    double restError = kNaN;           // error outside the region over the last 4 frames
    double freshSettledError = kNaN;   // the fresh renderer's region error over its last 4 frames
    double ghostLeft = kNaN;           // convergedError / restError: > 1 where the region settles
                                       // worse than the rest of the image
    double tolerance = kNaN;           // recovered: region error <= this (at the end; see runCase)
    int recoveryFrames = -1;           // frames after the last change until recovered, -1 never
    double excessOverFresh = kNaN;     // mean region error of the first 8 frames after the change
                                       // over the fresh renderer's, minus 1 (> 0: a ghost)
    double excessOverUnresized = kNaN; // a resize: the same over the renderer that never resized
                                       // (> 0: the resize cost the histories something)
    double staleAfter = kNaN;          // largest stale fraction after the last change
    double reusedAtChange = kNaN;      // fraction of geometry pixels that kept AO history then
    double keptUnseen = kNaN;          // ... though the camera before could not see their surface
    double stillFlicker = kNaN;        // the fresh renderer, converged and still
    double pathFlicker = kNaN;         // mean over the path frames
    size_t nonFinite = 0;              // over every image of every frame of the three renderers
    std::set<std::string> nonFiniteImages;
    // relMSE to the path tracer in the region: the tested renderer converged at the first
    // camera, the fresh one converged at the final camera, the tested one at the end; and the
    // fresh one outside the region.
    double truthStart = kNaN, truthFresh = kNaN, truthEnd = kNaN, truthRest = kNaN;
    Mask region;
    // The case's picture, panels of width x height side by side (RGBA, display-encoded).
    std::vector<std::string> panelNames;
    std::vector<Pixels> panels;
};

// Runs one case: the tested renderer along its timeline, a fresh one at the final camera and
// light, the converged image and (with truth samples) the path tracer (stability/run.cpp).
CaseResult runCase(vk::Context& ctx, const Case& c, const RunOptions& o,
                   const std::function<void(const std::string&)>& log = {});

} // namespace ssgi::stability
