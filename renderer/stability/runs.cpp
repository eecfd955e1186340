// The renderers of runs.h, and what each frame reads back from them.

#include "stability/runs.h"

#include <algorithm>

namespace ssgi::stability::detail {

namespace {

// Every image kept whole after the frame (none shares its memory with a later pass's), so
// that countNonFiniteImages reads them all.
RenderOptions rendererOptions(uint32_t width, uint32_t height) {
    return {width, height, "final", {"*"}};
}

// Every image of the last frame (a history pair's written side), counted for NaN/Inf. The
// light-view images change only when the light moves, so `withRsm` says whether to read them.
// An R32UI image holds keys, bit masks and counts, read back as their bits (texel_decode.h),
// not as numbers: it is left out.
size_t countNonFiniteImages(Renderer& r, bool withRsm, std::set<std::string>& offenders) {
    std::set<std::string> names;
    for (const auto& [name, bytes, pair] : r.frameGraph().imageMemory()) {
        const std::string& n = pair.empty() ? name : pair; // a pair is read by its name
        const graph::ImageRef ref = r.frameGraph().find(name);
        if (ref.valid() && r.frameGraph().image(ref).format == VK_FORMAT_R32_UINT) continue;
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

// The converged AO as the frame uses it: its history holds the mean unclamped (ao.comp), and
// the composite clamps it at 1, as the reference's visibility is.
Pixels readAo(Renderer& r) {
    Pixels ao = r.readImage("ao.history");
    for (size_t i = 0; i < ao.size(); i += 4)
        for (size_t c = 0; c < 3; ++c)
            ao[i + c] = std::min(ao[i + c], 1.0f);
    return ao;
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

// Fraction of geometry pixels whose AO (or SSDO) history continued this frame: rotation count
// above a fresh pixel's 1 (a history carried over a resize counts half a sample, so 1.5 after
// its first frame). The light does not reset these, so they show what the camera alone does.
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
        const bool continued = meta[4 * i + 3] > 1.0f;
        reused += continued;
        if (kept) (*kept)[i] = continued;
    }
    return geometry ? double(reused) / double(geometry) : kNaN;
}

} // namespace

TestedRun runTested(vk::Context& ctx, const Scene& scene, const Case& c,
                    const std::vector<Step>& steps, size_t lastChange, const RunOptions& o,
                    CaseResult& res, const Log& log) {
    const bool truthAo = c.truth == Truth::Ao;
    res.frames.resize(steps.size());
    TestedRun t;
    std::unique_ptr<Renderer> a;
    View previous;
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
        rec.reused = aoReused(*a, v, i == lastChange ? &t.keptAtChange : nullptr);
        if (i + 1 == o.warmup) {
            t.start = v;
            if (truthAo) t.startAo = readAo(*a);
        }
        if (i >= lastChange) {
            rec.sinceChange = int(i - lastChange);
            t.after.push_back(v.hdr);
        }
        if (i == lastChange) {
            t.changeLdr = a->readImage("ldr");
            res.reusedAtChange = rec.reused;
            t.before = previous;
        }
        if (log && (i + 1) % 20 == 0) log(c.name + ": frame " + std::to_string(i + 1));
        previous = std::move(v);
    }
    if (t.before.pixels() == 0) t.before = t.start;
    if (truthAo) t.endAo = readAo(*a);
    t.end = std::move(previous);
    return t;
}

// A resize changes every pixel, so no pixel of the same frame is left alone to show what the
// motion before it did to the histories (the other cases' "rest"): this timeline is its
// stand-in.
std::vector<Pixels> runUnresized(vk::Context& ctx, const Scene& scene,
                                 const std::vector<Step>& steps, size_t lastChange,
                                 CaseResult& res) {
    const Step& last = steps.back();
    std::vector<Pixels> unresized;
    Renderer u(ctx, scene, rendererOptions(last.width, last.height));
    for (size_t i = 0; i < steps.size(); ++i) {
        if (!sameLight(u.light(), steps[i].light)) u.setLight(steps[i].light);
        u.setTime(steps[i].time);
        u.renderFrame(steps[i].camera);
        res.nonFinite += countNonFiniteImages(u, i == 0, res.nonFiniteImages);
        if (i >= lastChange) unresized.push_back(readView(u, steps[i].camera).hdr);
    }
    return unresized;
}

// How a start without history fares, and the flicker of a still camera once converged. With
// the tested renderer's sampling patterns, frame k after the change takes the same pattern
// turns, VPL subsets, flux draws and refresh tile in both: what differs is the history alone,
// not which samples each drew (a frame whose samples happen to miss an occluder shows in both
// at once, not at different ages).
FreshRun runFresh(vk::Context& ctx, const Scene& scene, const Case& c, const Step& last,
                  size_t lastChange, const RunOptions& o, const View& testedEnd, CaseResult& res) {
    RenderOptions sameSamples = rendererOptions(last.width, last.height);
    sameSamples.patternStart = uint32_t(lastChange);
    Renderer f(ctx, scene, sameSamples);
    f.setLight(last.light);
    f.setTime(last.time);
    FreshRun run;
    View previous = testedEnd;
    for (uint32_t k = 0; k < o.converge + o.stillFrames; ++k) {
        f.renderFrame(last.camera);
        res.nonFinite += countNonFiniteImages(f, k == 0, res.nonFiniteImages);
        View v = readView(f, last.camera);
        if (k < o.converge) run.frames.push_back(v.hdr);
        if (k + 1 == o.converge && c.truth == Truth::Ao) run.ao = readAo(f);
        if (k >= o.converge) run.stillFlicker.push_back(flicker(previous, v, {}));
        previous = std::move(v);
    }
    return run;
}

// The running mean (cache_method 1) averages every frame. The thesis's rule would not do: its
// confidence is near 1 wherever the values are small, so its "converged" value keeps much of
// its first frame's noise. Nor would the tested settings: the same frames of the same settings
// are the same images, and a fresh start would be its own reference.
ConvergedRun runConverged(vk::Context& ctx, const Scene& scene, const Step& last,
                          const RunOptions& o, CaseResult& res) {
    Scene meanScene = scene;
    meanScene.settings.cache_method = 1;
    Settings& twice = meanScene.settings;
    twice.ao_directions = std::min(2 * scene.settings.ao_directions, 32);
    twice.indirect_vpls = std::min(2 * scene.settings.indirect_vpls, 1024);
    twice.ssdo_samples = std::min(2 * scene.settings.ssdo_samples, 64);
    twice.shadow_taps = std::min(2 * scene.settings.shadow_taps, 64);
    twice.shadow_directions = std::min(2 * scene.settings.shadow_directions, 64);
    twice.cache_samples = 1.0; // every frame its whole samples
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
    for (uint32_t k = 0; k < o.converge; ++k) {
        r.renderFrame(last.camera);
        res.nonFinite += countNonFiniteImages(r, k == 0, res.nonFiniteImages);
    }
    return {readView(r, last.camera), r.readImage("ldr")};
}

} // namespace ssgi::stability::detail
