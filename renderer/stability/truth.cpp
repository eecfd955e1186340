// The comparison with the path tracer of truth.h.

#include "stability/truth.h"

#include "stability/figures.h"

namespace ssgi::stability::detail {

namespace {

bool definedByOneView(Region region) {
    return region != Region::Disoccluded && region != Region::LightChanged &&
           region != Region::ObjectChanged && region != Region::Carried;
}

} // namespace

TruthImages compareWithTruth(CaseResult& res, const Case& c, const Scene& scene,
                             const std::vector<Step>& steps, const RunOptions& o,
                             const TestedRun& tested, const FreshRun& fresh,
                             const View& converged) {
    const bool truthAo = c.truth == Truth::Ao;
    const Step& last = steps.back();
    reference::ReferenceOptions ro;
    ro.mode = truthAo ? reference::Mode::Ao : reference::Mode::Full;
    ro.spp = truthAo ? 4 * o.truthSpp : o.truthSpp; // AO rays are short: more is cheap
    ro.width = last.width, ro.height = last.height;
    Scene lit = posedAt(scene, last.time);
    lit.light = last.light;
    TruthImages truth;
    truth.end = reference::cachedReference(lit, last.camera, ro).rgba;
    const Pixels& freshImage = truthAo ? fresh.ao : fresh.frames.back();
    const Mask rest = subtract(geometryMask(converged), res.region);
    res.truthFresh = maskedRelMse(freshImage, truth.end, res.region);
    res.truthEnd =
        maskedRelMse(truthAo ? tested.endAo : tested.after.back(), truth.end, res.region);
    res.truthRest = maskedRelMse(freshImage, truth.end, rest);
    if (definedByOneView(c.region)) {
        const View& start = tested.start;
        ro.width = start.width, ro.height = start.height;
        truth.start =
            reference::cachedReference(posedAt(scene, steps.front().time), start.camera, ro).rgba;
        res.truthStart = maskedRelMse(truthAo ? tested.startAo : start.hdr, truth.start,
                                      regionMask(c, start, start, start, scene));
    }
    return truth;
}

} // namespace ssgi::stability::detail
