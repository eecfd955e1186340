// runCase() of run.h: the timeline, the two renderers, and the figures drawn from them.

#include "stability/run.h"

#include "shared.h"
#include "stability/figures.h"

namespace ssgi::stability {

namespace detail {

// Linear radiance as the composite pass shows it (shared.h): exposure, ACES fit, sRGB.
Pixels tonemapped(const Pixels& hdr, float exposure) {
    Pixels out(hdr.size(), 1.0f);
    for (size_t i = 0; i < hdr.size(); i += 4)
        for (size_t c = 0; c < 3; ++c)
            out[i + c] = shader::encodeSrgb(shader::tonemapAces(hdr[i + c] * exposure));
    return out;
}

// An AO image (R) as display grey, its occlusion tripled so that a faint one shows.
Pixels grey(const Pixels& ao) {
    Pixels out(ao.size(), 1.0f);
    for (size_t i = 0; i < ao.size(); i += 4)
        out[i] = out[i + 1] = out[i + 2] = std::clamp(1.0f - 3.0f * (1.0f - ao[i]), 0.0f, 1.0f);
    return out;
}

} // namespace detail

CaseResult runCase(vk::Context& ctx, const Case& c, const RunOptions& o,
                   const std::function<void(const std::string&)>& log) {
    using namespace detail;
    Scene scene = loadScene(o.repository + "/" + c.scene);
    scene.settings = withOverrides(scene.settings, {o.settings.begin(), o.settings.end()}, c.scene);
    if (scene.cameraPath.empty()) throw InputError(c.scene + ": the case has no camera_path");
    const std::vector<Step> steps = timeline(c, scene, o);
    const size_t lastChange = indexOfLastChange(steps, scene);
    const Step& last = steps.back();
    const bool truthAo = c.truth == Truth::Ao;

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
    const View &start = tested.start, &converged = reference.view;
    const Pixels &startAo = tested.startAo, &endAo = tested.endAo, &changeLdr = tested.changeLdr;
    const Pixels &referenceAo = fresh.ao, &referenceLdr = reference.ldr;
    const std::vector<Pixels>&after = tested.after, &freshFrames = fresh.frames;

    measureFigures(res, c, scene, lastChange, tested, unresized, fresh, converged);
    const Mask rest = subtract(geometryMask(converged), res.region);

    // The picture: the tested renderer right after the change, its error there and at the end
    // (false colour, errorMap()), and the region over the converged image; AO cases show the
    // AO with the occluder on screen, after it left (fresh and tested) and the path tracer's.
    const metrics::Image target{last.width, last.height, converged.hdr};
    auto errorPanel = [&](const Pixels& image) {
        return metrics::errorMap({last.width, last.height, image}, target);
    };
    Pixels overlay = referenceLdr;
    for (size_t i = 0; i < res.region.size(); ++i)
        if (res.region[i])
            for (size_t ch = 0; ch < 3; ++ch)
                overlay[4 * i + ch] = 0.4f * overlay[4 * i + ch] + (ch == 1 ? 0.0f : 0.6f);
    {
        res.panels = {changeLdr, errorPanel(after.front()), errorPanel(after.back()), overlay};
        res.panelNames = {"tested, at the change", "its error there", "its error at the end",
                          "region"};
    }
    if (o.truthSpp > 0 && c.truth != Truth::None) {
        reference::ReferenceOptions ro;
        ro.mode = truthAo ? reference::Mode::Ao : reference::Mode::Full;
        ro.spp = truthAo ? 4 * o.truthSpp : o.truthSpp; // AO rays are short: more is cheap
        ro.width = last.width, ro.height = last.height;
        Scene lit = posedAt(scene, last.time);
        lit.light = last.light;
        const Pixels truth = reference::cachedReference(lit, last.camera, ro).rgba;
        Pixels truth0;
        res.truthFresh =
            maskedRelMse(truthAo ? referenceAo : freshFrames.back(), truth, res.region);
        res.truthEnd = maskedRelMse(truthAo ? endAo : after.back(), truth, res.region);
        res.truthRest = maskedRelMse(truthAo ? referenceAo : freshFrames.back(), truth, rest);
        // At the first camera, for regions that a single view defines.
        if (c.region != Region::Disoccluded && c.region != Region::LightChanged &&
            c.region != Region::ObjectChanged && c.region != Region::Carried) {
            ro.width = start.width, ro.height = start.height;
            truth0 =
                reference::cachedReference(posedAt(scene, steps.front().time), start.camera, ro)
                    .rgba;
            res.truthStart = maskedRelMse(truthAo ? startAo : start.hdr, truth0,
                                          regionMask(c, start, start, start, scene));
        }
        if (log) log(c.name + ": ground truth compared");
        if (!truthAo) {
            res.panels.push_back(tonemapped(truth, float(scene.settings.exposure)));
            res.panelNames.push_back("path-traced");
        } else {
            res.panels = {grey(startAo), grey(truth0), grey(referenceAo), grey(endAo), grey(truth)};
            res.panelNames = {"AO, occluder on screen", "path-traced", "AO, occluder gone (fresh)",
                              "(tested)", "path-traced"};
        }
    }
    return res;
}

} // namespace ssgi::stability
