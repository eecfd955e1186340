// The figures of a case (CaseResult in run.h), drawn from its renderers' frames (runs.h): the
// region, each frame's errors from the last change on, where the error settles, how long the
// region takes to recover, and the flicker.
#pragma once

#include "stability/runs.h"

namespace ssgi::stability::detail {

// Mean of the finite values among v[from, to); NaN where there are none.
double mean(const std::vector<double>& v, size_t from, size_t to);

// The case's region at the camera of `end`. `start`: the view at the end of the warm-up;
// `before`: the view just before the last change.
Mask regionMask(const Case& c, const View& start, const View& before, const View& end,
                const Scene& scene);

// Every figure of `res` but the path tracer's, in the region taken at the final camera.
void measureFigures(CaseResult& res, const Case& c, const Scene& scene, size_t lastChange,
                    const TestedRun& tested, const std::vector<Pixels>& unresized,
                    const FreshRun& fresh, const View& converged);

} // namespace ssgi::stability::detail
