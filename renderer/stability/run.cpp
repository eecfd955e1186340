// runCase() of run.h: the case's renderers along its timeline (runs.h), the figures drawn from
// them (figures.h), the comparison with the path tracer (truth.h) and the picture (panels.h).

#include "stability/run.h"

#include "stability/figures.h"
#include "stability/panels.h"

namespace ssgi::stability {

namespace {

// The case's scene with the run's setting overrides.
Scene loadCaseScene(const Case& c, const RunOptions& o) {
    Scene scene = loadScene(o.repository + "/" + c.scene);
    scene.settings = withOverrides(scene.settings, {o.settings.begin(), o.settings.end()}, c.scene);
    if (scene.cameraPath.empty()) throw InputError(c.scene + ": the case has no camera_path");
    return scene;
}

} // namespace

CaseResult runCase(vk::Context& ctx, const Case& c, const RunOptions& o,
                   const std::function<void(const std::string&)>& log) {
    using namespace detail;
    const Scene scene = loadCaseScene(c, o);
    const std::vector<Step> steps = timeline(c, scene, o);
    const size_t lastChange = indexOfLastChange(steps, scene);
    const Step& last = steps.back();

    CaseResult res;
    res.spec = c;
    res.width = last.width, res.height = last.height;
    const TestedRun tested = runTested(ctx, scene, c, steps, lastChange, o, res, log);
    const std::vector<Pixels> unresized = c.resizeScale > 0.0f
                                              ? runUnresized(ctx, scene, steps, lastChange, res)
                                              : std::vector<Pixels>{};
    const FreshRun fresh = runFresh(ctx, scene, c, last, lastChange, o, tested.end, res);
    const ConvergedRun reference = runConverged(ctx, scene, last, o, res);
    for (const FrameRecord& rec : res.frames)
        res.nonFinite += rec.nonFinite;
    if (log) log(c.name + ": reference converged");

    measureFigures(res, c, scene, lastChange, tested, unresized, fresh, reference.view);
    std::optional<TruthImages> truth;
    if (o.truthSpp > 0 && c.truth != Truth::None) {
        truth = compareWithTruth(res, c, scene, steps, o, tested, fresh, reference.view);
        if (log) log(c.name + ": ground truth compared");
    }
    drawPanels(res, c, scene, tested, fresh, reference, truth);
    return res;
}

} // namespace ssgi::stability
