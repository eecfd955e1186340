// Frame-by-frame measurements of the temporal cache: a still camera (the frame time should fall
// towards G-buffer + direct + composite as pixels converge, and the error should fall), and the
// scene's camera path with the cache off and on (the thesis's Table 4.1).
#include "bench.h"

#include "scene/camera.h"

#include <algorithm>

namespace ssgi::bench {

namespace {

struct Method {
    std::string label;
    SettingOverrides settings;
};

// The cache with few samples a frame, which only its accumulation over frames can afford (the
// thesis's PCF 9 + cache, and likewise AO 4x2 of 8x4 and 64 VPLs of 512), blended by the
// running mean: along a moving camera the thesis rule keeps much of a noisy first frame. Its
// 64 VPLs a frame also need the bounce's history while the camera moves (a blur budget of 4
// px^2, where the default, 0, computes it anew): along the bunny's path at 256x256 the error
// was 0.0060 with it and 0.0084 without, at the same cost (docs/temporal-cache.md). Its counts
// are a frame's whole share (cache_samples 1), not halved again by the default share.
const Method& cheapFrames() {
    static const Method method = {"cache: running mean, cheap frames",
                                  {{"cache", 1},
                                   {"cache_method", 1},
                                   {"ao_directions", 4},
                                   {"ao_steps", 2},
                                   {"indirect_vpls", 64},
                                   {"shadow_variant", 0},
                                   {"shadow_taps", 9},
                                   {"cache_blur_indirect", 4.0},
                                   {"cache_samples", 1.0}}};
    return method;
}

// The world cache's bounce with every sample a frame of the effects the cache accumulates
// (cache_samples 1: the AO's 8 directions), where the default takes half of them and the
// accumulation supplies the rest: what the share buys along a moving camera.
const Method& worldCacheEverySample() {
    static const Method method = {"cache: world cache, every sample a frame",
                                  {{"cache", 1}, {"indirect_method", 3}, {"cache_samples", 1.0}}};
    return method;
}

const std::vector<Method>& cacheMethods() {
    static const std::vector<Method> methods = {
        {"cache: thesis rule", {{"cache", 1}, {"cache_method", 0}}},
        {"cache: running mean", {{"cache", 1}, {"cache_method", 1}}},
        cheapFrames()};
    return methods;
}

// Each method's frames timed at the timing size, and (with options.error) its error at the
// error size against `references[k]` after frame errorAt[k].
Json measureMethods(vk::Context& ctx, const Scene& scene, const std::vector<Method>& methods,
                    const Options& options, uint32_t frames,
                    const std::function<Camera(uint32_t)>& cameraOf,
                    const std::vector<uint32_t>& errorAt, const std::vector<Reference>& references,
                    Progress& progress, const std::string& what) {
    std::vector<Scene> scenes;
    for (const Method& method : methods)
        scenes.push_back(withSettings(scene, method.settings));
    progress.step(what + ": " + std::to_string(frames) + " frames, timed");
    std::vector<FrameLog> logs(methods.size());
    interleaved(ctx, scenes, {options.width, options.height}, frames, cameraOf,
                [&](size_t m, uint32_t, const Renderer& r, double wall) { logs[m].add(r, wall); });
    Json result = Json::array();
    for (size_t m = 0; m < methods.size(); ++m) {
        Json j = logs[m].json();
        j["label"] = methods[m].label;
        j["settings"] = settingsJson(methods[m].settings);
        result.push_back(j);
    }
    if (!options.error) return result;
    progress.step(what + ": " + std::to_string(frames) + " frames, error");
    interleaved(ctx, scenes, {options.errorWidth, options.errorHeight}, frames, cameraOf,
                [&](size_t m, uint32_t f, Renderer& r, double) {
                    const auto k = std::find(errorAt.begin(), errorAt.end(), f) - errorAt.begin();
                    if (size_t(k) == errorAt.size()) return;
                    const Error e = hdrError(r, references[k]);
                    result[m]["rel_mse"].push_back(e.relMse);
                    result[m]["ssim"].push_back(e.ssim);
                });
    return result;
}

} // namespace

size_t cachedSeriesSteps(const Options& options) {
    return options.error ? 2 : 1;
}

Json cachedSeries(vk::Context& ctx, const Scene& scene, const Options& options,
                  const Reference& reference, Progress& progress) {
    std::vector<uint32_t> everyFrame(options.seriesFrames);
    for (uint32_t f = 0; f < options.seriesFrames; ++f)
        everyFrame[f] = f;
    const std::vector<Reference> references(options.seriesFrames, reference);
    const std::vector<Method> methods(
        cacheMethods().begin(),
        cacheMethods().begin() + std::min(cacheMethods().size(), size_t(options.seriesMethods)));
    return measureMethods(
        ctx, scene, methods, options, options.seriesFrames, [&](uint32_t) { return scene.camera; },
        everyFrame, references, progress, "still camera, cache");
}

namespace {

// The camera of frame f of a path of `pathFrames` frames over the scene's camera path.
std::function<Camera(uint32_t)> pathCamera(const Scene& scene, uint32_t pathFrames) {
    if (scene.cameraPath.empty())
        throw InputError(scene.sourcePath + ": the scene has no camera_path to walk");
    const float duration = scene.cameraPath.keys.back().time;
    return [&scene, pathFrames, duration](uint32_t f) {
        return cameraAt(scene.cameraPath, pathFrames > 1 ? duration * f / (pathFrames - 1) : 0.0f);
    };
}

// The path's frames whose error is measured: evenly spaced, the last frame among them.
std::vector<uint32_t> pathErrorFrames(uint32_t pathFrames, uint32_t errorFrames) {
    std::vector<uint32_t> errorAt;
    for (uint32_t k = 1; k <= errorFrames; ++k)
        errorAt.push_back(uint32_t((uint64_t(pathFrames - 1) * k) / errorFrames));
    return errorAt;
}

// The references of `frames`, each a step of `progress`.
std::vector<Reference> referencesAt(const Scene& scene, const Options& options,
                                    const std::function<Camera(uint32_t)>& cameraOf,
                                    const std::vector<uint32_t>& frames, Progress& progress) {
    std::vector<Reference> references;
    for (uint32_t f : frames) {
        progress.step("reference of frame " + std::to_string(f));
        references.push_back(fullReference(scene, cameraOf(f), options));
    }
    return references;
}

// What the cache does where it used to fail (docs/stability.md), each undone alone
// beside the default that has them all, with the guard band (off by default) on, and the cache
// off: the cost of each along the camera path and on a settled still camera.
const std::vector<Method>& cacheFixMethods() {
    static const std::vector<Method> methods = {
        {"cache off", {{"cache", 0}}},
        {"every fix (default)", {}},
        {"no automatic cut", {{"cache_cut_angle_deg", 180.0}, {"cache_cut_distance", 1e9}}},
        {"no thin-geometry reprojection", {{"cache_thin_geometry", 0}}},
        {"no screen-edge restart", {{"cache_screen_edge", 0}}},
        {"bounce history kept while moving", {{"cache_blur_indirect", 4.0}}},
        {"guard band 16 px", {{"guard_band", 16}}}};
    return methods;
}

} // namespace

Json walkthrough(vk::Context& ctx, const Scene& scene, const Options& options, uint32_t pathFrames,
                 uint32_t errorFrames) {
    const std::function<Camera(uint32_t)> cameraOf = pathCamera(scene, pathFrames);
    const std::vector<uint32_t> errorAt = pathErrorFrames(pathFrames, errorFrames);
    // "cache off" is the uncached frame with the interleaved bounce (indirect_method 1), the
    // yardstick every speed-up is taken against; "cache off, world cache" the world cache's
    // uncached frame (what a camera cut costs it); "cache: thesis rule" the interleaved bounce
    // cached with every sample a frame and only converged pixels reused, as the thesis caches
    // it; "cache: world cache" the defaults.
    std::vector<Method> methods = {
        {"cache off", {{"cache", 0}, {"indirect_method", 1}}},
        {"cache off, world cache", {{"cache", 0}, {"indirect_method", 3}}},
        {"cache: thesis rule",
         {{"cache", 1}, {"indirect_method", 1}, {"cache_samples", 1.0}, {"cache_reuse_moving", 0}}},
        {"cache: world cache", {{"cache", 1}, {"indirect_method", 3}}},
        worldCacheEverySample()};
    if (!options.methods.empty()) {
        methods.clear();
        for (const auto& [label, settings] : options.methods)
            methods.push_back({label, settings});
    }
    Progress progress("  walkthrough " + scene.sourcePath,
                      1 + (options.error ? 1 + errorAt.size() : 0));
    const std::vector<Reference> references =
        options.error ? referencesAt(scene, options, cameraOf, errorAt, progress)
                      : std::vector<Reference>{};
    Json result = {{"frames", pathFrames}, {"error_frames", errorAt}};
    result["runs"] = measureMethods(ctx, scene, methods, options, pathFrames, cameraOf, errorAt,
                                    references, progress, "camera path, cache off and on");
    progress.done();
    return result;
}

Json cacheFixes(vk::Context& ctx, const Scene& scene, const Options& options, uint32_t pathFrames,
                uint32_t errorFrames, uint32_t stillFrames) {
    const std::function<Camera(uint32_t)> cameraOf = pathCamera(scene, pathFrames);
    const std::vector<uint32_t> errorAt = pathErrorFrames(pathFrames, errorFrames);
    const Camera last = cameraOf(pathFrames - 1);
    const std::function<Camera(uint32_t)> still = [&last](uint32_t) { return last; };
    const std::vector<uint32_t> stillErrorAt = {stillFrames - 1};
    Progress progress("  cache fixes " + scene.sourcePath,
                      2 + (options.error ? 2 + errorAt.size() + 1 : 0));
    std::vector<Reference> references, stillReferences;
    if (options.error) {
        references = referencesAt(scene, options, cameraOf, errorAt, progress);
        stillReferences = referencesAt(scene, options, still, stillErrorAt, progress);
    }
    Json path = {{"frames", pathFrames}, {"error_frames", errorAt}};
    path["runs"] = measureMethods(ctx, scene, cacheFixMethods(), options, pathFrames, cameraOf,
                                  errorAt, references, progress, "camera path");
    Json settled = {{"frames", stillFrames}, {"error_frames", stillErrorAt}};
    settled["runs"] =
        measureMethods(ctx, scene, cacheFixMethods(), options, stillFrames, still, stillErrorAt,
                       stillReferences, progress, "still camera at the path's end");
    progress.done();
    return {{"walkthrough", path}, {"still", settled}};
}

} // namespace ssgi::bench
