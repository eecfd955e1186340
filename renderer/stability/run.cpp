// runCase() of run.h: the timeline, the two renderers, and the figures drawn from them.

#include "stability/run.h"

#include "shared.h"
#include "stability/runs.h"

namespace ssgi::stability {

namespace detail {

// `start`: the view at the end of the warm-up; `before`: the view just before the last change.
Mask regionMask(const Case& c, const View& start, const View& before, const View& end,
                const Scene& scene) {
    const Pixels& oldHdr = start.hdr;
    switch (c.region) {
    case Region::Disoccluded:
        return disoccludedMask(start, end);
    case Region::Carried:
        return subtract(geometryMask(end), unseenMask(before, end));
    case Region::Thin:
        return thinMask(end, 3, 1.15f, 1);
    case Region::NearOccluder:
        return nearBoxMask(end, c.occluder, aoRadius(scene));
    case Region::LightChanged:
    case Region::ObjectChanged:
        return changedMask(oldHdr, end.hdr, geometryMask(end), 0.2);
    case Region::Grazing:
        return grazingMask(end, 0.2f);
    case Region::DepthEdges:
        return depthEdgeMask(end, 1.2f, 2);
    case Region::Geometry:
        return geometryMask(end);
    }
    return {};
}

double mean(const std::vector<double>& v, size_t from, size_t to) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = from; i < std::min(to, v.size()); ++i)
        if (std::isfinite(v[i])) sum += v[i], ++n;
    return n ? sum / double(n) : kNaN;
}

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
    const View &start = tested.start, &before = tested.before, &converged = reference.view;
    const Pixels &startAo = tested.startAo, &endAo = tested.endAo, &changeLdr = tested.changeLdr;
    const Pixels &referenceAo = fresh.ao, &referenceLdr = reference.ldr;
    const Mask& keptAtChange = tested.keptAtChange;
    const std::vector<Pixels>&after = tested.after, &freshFrames = fresh.frames;
    res.stillFlicker = mean(fresh.stillFlicker, 0, fresh.stillFlicker.size());

    // The figures, in the region taken at the final camera.
    res.region =
        c.region == Region::Carried ? keptAtChange : regionMask(c, start, before, converged, scene);
    res.geometryPixels = metrics::countInside(geometryMask(converged));
    if (c.region == Region::Carried) { // kept, though the camera before could not see it
        const Mask unseen = unseenMask(before, converged);
        size_t invented = 0;
        for (size_t i = 0; i < unseen.size(); ++i)
            invented += unseen[i] && keptAtChange[i];
        res.keptUnseen = double(invented) / double(res.geometryPixels);
    }
    res.regionPixels = metrics::countInside(res.region);
    const Mask rest = subtract(geometryMask(converged), res.region);
    std::vector<double> errors, rests, freshErrors;
    for (size_t k = 0; k < after.size(); ++k) {
        FrameRecord& rec = res.frames[lastChange + k];
        rec.error = maskedRelMse(after[k], converged.hdr, res.region);
        rec.errorRest = k < unresized.size() ? maskedRelMse(unresized[k], converged.hdr, res.region)
                                             : maskedRelMse(after[k], converged.hdr, rest);
        if (k < freshFrames.size()) {
            rec.freshError = maskedRelMse(freshFrames[k], converged.hdr, res.region);
            rec.freshRest = maskedRelMse(freshFrames[k], converged.hdr, rest);
        }
        if (c.movesLight || c.region == Region::ObjectChanged)
            rec.stale = staleFraction(after[k], start.hdr, converged.hdr, res.region);
        errors.push_back(rec.error), rests.push_back(rec.errorRest);
        freshErrors.push_back(rec.freshError);
        if (k > 0 && std::isfinite(rec.stale))
            res.staleAfter =
                std::isfinite(res.staleAfter) ? std::max(res.staleAfter, rec.stale) : rec.stale;
    }
    res.convergedError =
        mean(errors, errors.size() - std::min<size_t>(4, errors.size()), errors.size());
    res.restError = mean(rests, rests.size() - std::min<size_t>(4, rests.size()), rests.size());
    res.ghostLeft = res.convergedError / res.restError;
    // Recovered: the region's error within twice that of the rest of the same frame, whose
    // history the change left alone (so motion's own damage is not charged to the region), or
    // within twice a fresh start's at the same age, whichever is larger (once the camera holds
    // still the rest accumulates again too, and a region as good as a fresh start has nothing
    // left to recover). A resize's region is the whole image: its "rest" is the same frame of
    // the timeline rendered at the final size throughout (the motion's damage without the
    // resize's); where there is no rest at all, within twice where a fresh start settles.
    const double freshSettled =
        mean(freshErrors, freshFrames.size() - std::min<size_t>(4, freshFrames.size()),
             freshFrames.size());
    res.freshSettledError = freshSettled;
    std::vector<double> relative;
    for (size_t k = 0; k < errors.size(); ++k) {
        double tolerance = 2.0 * (std::isfinite(rests[k]) ? rests[k] : freshSettled);
        // The fresh start renders `converge` frames, one fewer than the hold's after the change:
        // past them it has settled.
        const double fresh = std::isfinite(freshErrors[k]) ? freshErrors[k] : freshSettled;
        if (std::isfinite(rests[k]) && std::isfinite(fresh))
            tolerance = std::max(tolerance, 2.0 * fresh);
        relative.push_back(errors[k] / tolerance);
    }
    res.tolerance = 2.0 * (std::isfinite(res.restError) ? res.restError : freshSettled);
    // An empty region (a cut that kept no history) has nothing to recover.
    res.recoveryFrames = res.regionPixels == 0 ? 0 : framesUntilWithin(relative, 1.0);
    res.excessOverFresh = mean(errors, 0, 8) / mean(freshErrors, 0, 8) - 1.0;
    if (!unresized.empty()) res.excessOverUnresized = mean(errors, 0, 8) / mean(rests, 0, 8) - 1.0;
    std::vector<double> pathFlicker;
    for (const FrameRecord& rec : res.frames)
        if (std::string(rec.phase) == "path") pathFlicker.push_back(rec.flicker);
    res.pathFlicker = mean(pathFlicker, 0, pathFlicker.size());

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
