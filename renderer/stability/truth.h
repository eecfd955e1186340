// A case's comparison with the path tracer: the relMSE of the tested and the fresh renderer to
// its image at the final camera, and of the tested one to its image at the first camera.
#pragma once

#include "stability/runs.h"

namespace ssgi::stability::detail {

// The path tracer's images (AO alone for Truth::Ao, else the final image).
struct TruthImages {
    Pixels end;   // at the final camera, light and object poses
    Pixels start; // at the first camera; empty where a single view does not define the region
};

// Fills the truth figures of `res` (its region already taken): the path-traced images, rendered
// or read from the reference cache, against the renderers' AO or HDR images.
TruthImages compareWithTruth(CaseResult& res, const Case& c, const Scene& scene,
                             const std::vector<Step>& steps, const RunOptions& o,
                             const TestedRun& tested, const FreshRun& fresh, const View& converged);

} // namespace ssgi::stability::detail
