// The renderers a case runs: the tested one along the timeline, the same timeline at the final
// size throughout (a resize), a fresh one at the final camera, and the converged reference
// there. Each records its frames' NaN/Inf (and the tested one its frame records) in the result.
#pragma once

#include "stability/run.h"
#include "stability/timeline.h"

namespace ssgi::stability::detail {

using Log = std::function<void(const std::string&)>;

// What the figures and the picture take of the tested renderer's frames.
struct TestedRun {
    View start;                // at the end of the warm-up
    View before;               // just before the last change (`start` where nothing changed)
    View end;                  // the last frame
    Pixels startAo, endAo;     // its AO at the end of the warm-up and at the end (AO ground truth)
    Pixels changeLdr;          // the display image at the last change
    Mask keptAtChange;         // pixels whose AO history continued at the last change
    std::vector<Pixels> after; // the HDR frames from the last change on
};

// The tested renderer along `steps`: a new renderer at each new size, going on from the old.
// Fills res.frames (all but the errors) and res.reusedAtChange.
TestedRun runTested(vk::Context& ctx, const Scene& scene, const Case& c,
                    const std::vector<Step>& steps, size_t lastChange, const RunOptions& o,
                    CaseResult& res, const Log& log);

// The HDR frames from the last change on of the same timeline rendered at the final size
// throughout, the same samples in the same frames.
std::vector<Pixels> runUnresized(vk::Context& ctx, const Scene& scene,
                                 const std::vector<Step>& steps, size_t lastChange,
                                 CaseResult& res);

struct FreshRun {
    std::vector<Pixels> frames;       // HDR, the first `converge` frames
    Pixels ao;                        // its AO once converged (AO ground truth)
    std::vector<double> stillFlicker; // of each frame after those
};

// A fresh renderer with the tested settings at the final camera, light and size, its sampling
// patterns starting where the tested renderer's stood at the last change. `testedEnd`: the
// tested renderer's last frame, which the first still frame's flicker is taken against where
// `o.converge` is 0.
FreshRun runFresh(vk::Context& ctx, const Scene& scene, const Case& c, const Step& last,
                  size_t lastChange, const RunOptions& o, const View& testedEnd, CaseResult& res);

struct ConvergedRun {
    View view;  // the converged image and its geometry
    Pixels ldr; // its display image
};

// The converged image at the final camera: the running mean, twice the samples a frame,
// sampling patterns that no other renderer of the case takes.
ConvergedRun runConverged(vk::Context& ctx, const Scene& scene, const Step& last,
                          const RunOptions& o, CaseResult& res);

} // namespace ssgi::stability::detail
