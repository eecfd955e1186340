// runCase() of run.h: the timeline, the two renderers, and the figures drawn from them.

#include "stability/run.h"

#include "shared.h"
#include "stability/timeline.h"

namespace ssgi::stability {

namespace detail {

// Every image kept whole after the frame (none shares its memory with a later pass's), so
// that countNonFiniteImages reads them all.
RenderOptions rendererOptions(uint32_t width, uint32_t height) {
    return {width, height, "final", {"*"}};
}

// Every image of the last frame (a history pair's written side), counted for NaN/Inf. The
// light-view images change only when the light moves, so `withRsm` says whether to read them.
size_t countNonFiniteImages(Renderer& r, bool withRsm, std::set<std::string>& offenders) {
    std::set<std::string> names;
    for (const auto& [name, bytes, pair] : r.frameGraph().imageMemory()) {
        const std::string& n = pair.empty() ? name : pair; // a pair is read by its name
        if (withRsm || !n.starts_with("rsm.")) names.insert(n);
    }
    size_t total = 0;
    for (const std::string& name : names) {
        const size_t bad = countNonFinite(r.readImage(name));
        if (bad) offenders.insert(name);
        total += bad;
    }
    return total;
}

View readView(Renderer& r, const Camera& camera) {
    View v{r.size().width,
           r.size().height,
           camera,
           r.readImage("hdr"),
           r.readImage("gbuffer.position"),
           r.readImage("gbuffer.normal"),
           r.readImage("gbuffer.albedo")};
    return v;
}

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

// Fraction of geometry pixels whose AO (or SSDO) history continued this frame: rotation count
// above 1. The light does not reset these, so they show what the camera alone does.
double aoReused(Renderer& r, const View& v, Mask* kept = nullptr) {
    const char* name = r.frameGraph().find("ao.count A").valid()     ? "ao.meta"
                       : r.frameGraph().find("ssdo.count A").valid() ? "ssdo.meta"
                                                                     : nullptr;
    if (!name) return kNaN;
    const Pixels meta = r.readImage(name);
    size_t reused = 0, geometry = 0;
    if (kept) kept->assign(v.pixels(), 0);
    for (size_t i = 0; i < v.pixels(); ++i) {
        if (!v.geometry(i)) continue;
        ++geometry;
        const bool continued = meta[4 * i + 3] > 1.5f;
        reused += continued;
        if (kept) (*kept)[i] = continued;
    }
    return geometry ? double(reused) / double(geometry) : kNaN;
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
    res.frames.resize(steps.size());
    std::unique_ptr<Renderer> a;
    View previous, start, before;
    Pixels startAo, endAo, changeLdr;
    Mask keptAtChange;         // pixels whose AO history continued at the last change
    std::vector<Pixels> after; // the tested renderer's HDR frames from the last change on
    for (size_t i = 0; i < steps.size(); ++i) {
        const Step& s = steps[i];
        const bool fresh = !a || a->size().width != s.width || a->size().height != s.height;
        if (fresh) { // the first frame, or a resize: the new size goes on from the old
            auto next = std::make_unique<Renderer>(ctx, scene, rendererOptions(s.width, s.height));
            if (a) next->continueFrom(*a);
            a = std::move(next);
        }
        const bool lightMoved = !sameLight(a->light(), s.light);
        if (lightMoved) a->setLight(s.light);
        a->setTime(s.time);
        a->renderFrame(s.camera);
        FrameRecord& rec = res.frames[i];
        rec.phase = s.phase;
        rec.nonFinite = countNonFiniteImages(*a, fresh || lightMoved, res.nonFiniteImages);
        View v = readView(*a, s.camera);
        if (i > 0) rec.flicker = flicker(previous, v, {});
        rec.reused = aoReused(*a, v, i == lastChange ? &keptAtChange : nullptr);
        if (i + 1 == o.warmup) {
            start = v;
            if (truthAo) startAo = a->readImage("ao.history");
        }
        if (i >= lastChange) {
            rec.sinceChange = int(i - lastChange);
            after.push_back(v.hdr);
        }
        if (i == lastChange) {
            changeLdr = a->readImage("ldr");
            res.reusedAtChange = rec.reused;
            before = previous;
        }
        if (log && (i + 1) % 20 == 0) log(c.name + ": frame " + std::to_string(i + 1));
        previous = std::move(v);
    }
    if (before.pixels() == 0) before = start;
    if (truthAo) endAo = a->readImage("ao.history");
    a.reset();

    // A resize changes every pixel, so no pixel of the same frame is left alone to show what the
    // motion before it did to the histories (the other cases' "rest"). Its stand-in: the same
    // timeline rendered at the final size throughout, the same samples in the same frames.
    std::vector<Pixels> unresized;
    if (c.resizeScale > 0.0f) {
        Renderer u(ctx, scene, rendererOptions(last.width, last.height));
        for (size_t i = 0; i < steps.size(); ++i) {
            if (!sameLight(u.light(), steps[i].light)) u.setLight(steps[i].light);
            u.setTime(steps[i].time);
            u.renderFrame(steps[i].camera);
            res.nonFinite += countNonFiniteImages(u, i == 0, res.nonFiniteImages);
            if (i >= lastChange) unresized.push_back(readView(u, steps[i].camera).hdr);
        }
    }

    // A fresh renderer with the tested settings at the final camera, light and size: how a
    // start without history fares, and the flicker of a still camera once converged. Its
    // sampling patterns start where the tested renderer's stood at the last change, so that
    // frame k after the change takes the same pattern turns, VPL subsets, flux draws and refresh
    // tile in both: what differs is the history alone, not which samples each drew (a frame
    // whose samples happen to miss an occluder shows in both at once, not at different ages).
    RenderOptions sameSamples = rendererOptions(last.width, last.height);
    sameSamples.patternStart = uint32_t(lastChange);
    Renderer f(ctx, scene, sameSamples);
    f.setLight(last.light);
    f.setTime(last.time);
    std::vector<Pixels> freshFrames;
    std::vector<double> stillFlicker;
    Pixels referenceAo;
    for (uint32_t k = 0; k < o.converge + o.stillFrames; ++k) {
        f.renderFrame(last.camera);
        res.nonFinite += countNonFiniteImages(f, k == 0, res.nonFiniteImages);
        View v = readView(f, last.camera);
        if (k < o.converge) freshFrames.push_back(v.hdr);
        if (k + 1 == o.converge && truthAo) referenceAo = f.readImage("ao.history");
        if (k >= o.converge) stillFlicker.push_back(flicker(previous, v, {}));
        previous = std::move(v);
    }
    res.stillFlicker = mean(stillFlicker, 0, stillFlicker.size());
    // The converged image: a still camera's, accumulated by the running mean (cache_method 1),
    // which averages every frame, from twice the samples a frame. The thesis's rule would not
    // do: its confidence is near 1 wherever the values are small, so its "converged" value
    // keeps much of its first frame's noise. Nor would the tested settings: the same frames
    // of the same settings are the same images, and a fresh start would be its own reference.
    Scene meanScene = scene;
    meanScene.settings.cache_method = 1;
    Settings& twice = meanScene.settings;
    twice.ao_directions = std::min(2 * scene.settings.ao_directions, 32);
    twice.indirect_vpls = std::min(2 * scene.settings.indirect_vpls, 1024);
    twice.ssdo_samples = std::min(2 * scene.settings.ssdo_samples, 64);
    twice.shadow_taps = std::min(2 * scene.settings.shadow_taps, 64);
    // Its sampling patterns start where neither the tested renderer's nor the fresh start's
    // have been (4099 frames on: not a whole number of the patterns' turns), so that it shares
    // no sample with either: a reference that took the fresh start's own samples (its pattern
    // turns, its VPL subsets and flux draws, at twice the count) would put the fresh start
    // nearer to it than the samples warrant, and every ratio to a fresh start would be inflated.
    RenderOptions independent = rendererOptions(last.width, last.height);
    independent.patternStart = 4099;
    Renderer r(ctx, meanScene, independent);
    r.setLight(last.light);
    r.setTime(last.time);
    View converged;
    for (uint32_t k = 0; k < o.converge; ++k) {
        r.renderFrame(last.camera);
        res.nonFinite += countNonFiniteImages(r, k == 0, res.nonFiniteImages);
    }
    converged = readView(r, last.camera);
    const Pixels referenceLdr = r.readImage("ldr");
    for (const FrameRecord& rec : res.frames)
        res.nonFinite += rec.nonFinite;
    if (log) log(c.name + ": reference converged");

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
