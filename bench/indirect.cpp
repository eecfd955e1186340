// The one-bounce indirect light's methods side by side (docs/bench-indirect.md): the cost of the
// light relative to the rest of an uncached frame, (frame with it - frame without) / frame
// without, from frames interleaved renderer by renderer; and at the error size, against the
// path-traced reference, one uncached frame and the converged cache (still camera), over the
// whole image and inside a band around depth edges (where an upsampling leaves a staircase),
// and how far one frame lies from its own converged image (the noise a viewer sees).
#include "bench.h"

#include "app/cli.h"
#include "metrics/metrics.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace ssgi::bench {

namespace {

// Uncached frames whose figures are averaged: the patterns' first places in their sequence.
constexpr uint32_t kOneFrameDraws = 4;

struct Method {
    std::string label;
    SettingOverrides settings;
};

std::vector<Method> methodsOf(const Options& options) {
    std::vector<Method> methods = {{"off", {{"indirect", 0}}}};
    if (options.methods.empty()) {
        methods.push_back({"thesis: half resolution, 512 VPLs",
                           {{"indirect_method", 0}, {"indirect_vpls", 512}}});
        methods.push_back({"interleaved", {{"indirect_method", 1}}});
        methods.push_back({"importance", {{"indirect_method", 2}}});
        methods.push_back({"world cache", {{"indirect_method", 3}}});
    }
    for (const auto& [label, settings] : options.methods)
        methods.push_back({label, settings});
    return methods;
}

// Pixels within `band` pixels (chessboard distance) of a depth edge: neighbours whose distances
// to the camera differ by more than 5%, or geometry beside background.
metrics::Mask depthEdgeBand(const std::vector<float>& position, uint32_t w, uint32_t h,
                            glm::vec3 camera, int band) {
    std::vector<float> distance(size_t(w) * h, -1.0f);
    for (size_t i = 0; i < distance.size(); ++i)
        if (position[4 * i + 3] != 0.0f)
            distance[i] = glm::length(
                glm::vec3(position[4 * i], position[4 * i + 1], position[4 * i + 2]) - camera);
    auto edge = [](float a, float b) {
        if ((a < 0.0f) != (b < 0.0f)) return true;
        return a >= 0.0f && std::abs(a - b) > 0.05f * std::min(a, b);
    };
    metrics::Mask edges(distance.size(), 0);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            if ((x + 1 < w && edge(distance[i], distance[i + 1])) ||
                (y + 1 < h && edge(distance[i], distance[i + w])))
                edges[i] = 1;
        }
    metrics::Mask mask(distance.size(), 0);
    for (int y = 0; y < int(h); ++y)
        for (int x = 0; x < int(w); ++x) {
            const size_t i = size_t(y) * w + x;
            if (distance[i] < 0.0f) continue;
            for (int dy = -band; dy <= band && !mask[i]; ++dy)
                for (int dx = -band; dx <= band; ++dx) {
                    const int qx = x + dx, qy = y + dy;
                    if (qx >= 0 && qy >= 0 && qx < int(w) && qy < int(h) &&
                        edges[size_t(qy) * w + qx]) {
                        mask[i] = 1;
                        break;
                    }
                }
        }
    return mask;
}

double relMse(const metrics::Image& test, const metrics::Image& truth, const metrics::Mask& mask) {
    return metrics::errorFigures(test, truth, mask, {}).relMse; // no SSIM: not reported
}

Json figures(const metrics::Image& test, const metrics::Image& truth, const metrics::Mask& mask) {
    return {{"relmse", relMse(test, truth, mask)}, {"pixels", metrics::countInside(mask)}};
}

} // namespace

Json indirectComparison(vk::Context& ctx, const Scene& scene, const Options& options,
                        uint32_t convergedFrames) {
    const std::vector<Method> methods = methodsOf(options);
    Progress progress("  " + scene.sourcePath + " indirect",
                      options.warmup + options.frames + 2 + 2 * methods.size());
    Json result;

    // The cost, cache off, frames interleaved.
    std::vector<Scene> scenes;
    for (const Method& m : methods) {
        scenes.push_back(withSettings(scene, m.settings));
        scenes.back().settings.cache = false;
    }
    std::vector<FrameLog> logs(methods.size());
    interleaved(
        ctx, scenes, {options.width, options.height}, options.warmup + options.frames,
        [&](uint32_t) { return scene.camera; },
        [&](size_t i, uint32_t, Renderer& r, double wall) { logs[i].add(r, wall); }, &progress,
        "timing");
    auto timed = [&](const std::vector<double>& all) {
        return std::vector<double>(all.begin() + std::min<size_t>(options.warmup, all.size()),
                                   all.end());
    };
    const double off = cli::median(timed(logs[0].totals));

    // The error: reference, then each method's one frame and converged image.
    progress.step("reference");
    const Reference reference = fullReference(scene, scene.camera, options);
    const VkExtent2D errorSize{options.errorWidth, options.errorHeight};
    const metrics::Image truth{errorSize.width, errorSize.height, reference.rgba};
    // The bounce alone (outgoing radiance of one bounce, no sky), for the term's own error, and
    // the direct light and the sky light alone, for where the whole image's error comes from.
    auto referenceOf = [&](reference::Mode mode) {
        return modeReference(scene, scene.camera, options, mode).rgba;
    };
    const metrics::Image bounceTruth{errorSize.width, errorSize.height,
                                     referenceOf(reference::Mode::Indirect)};
    const std::vector<float> directTruth = referenceOf(reference::Mode::Direct);
    const std::vector<float> skyTruth = referenceOf(reference::Mode::Sky);
    // The renderer's bounce (irradiance / pi) times the albedo: outgoing radiance, as the
    // reference's (tests/test_accuracy.cpp does the same).
    auto bounceOf = [&](Renderer& r, const std::string& image) {
        std::vector<float> bounce = r.readImage(image);
        const std::vector<float> albedo = r.readImage("gbuffer.albedo");
        for (size_t i = 0; i < bounce.size(); ++i)
            bounce[i] = i % 4 == 3 ? 1.0f : bounce[i] * albedo[i];
        return metrics::Image{errorSize.width, errorSize.height, bounce};
    };
    // The image that holds a frame's bounce: the cache's blended history, the raw value
    // without the cache, or the world cache's lookup (indirect_method 3, which keeps no
    // screen-space history).
    auto bounceImage = [](const Scene& s) -> std::string {
        if (s.settings.indirect_method == 3) return "world.indirect";
        return s.settings.cache ? "indirect.history" : "indirect";
    };
    metrics::Mask geometry, band;
    // Means over the geometry of each term, real-time (converged) against the reference: the
    // sky term is what the composite adds beyond the direct light and the bounce.
    auto termMeans = [&](Renderer& r, const Scene& cached) {
        const std::vector<float> hdr = r.readImage("hdr"), direct = r.readImage("direct");
        const std::vector<float> bounce = bounceOf(r, bounceImage(cached)).rgba;
        double sums[6] = {};
        size_t n = 0;
        for (size_t i = 0; i < geometry.size(); ++i) {
            if (!geometry[i]) continue;
            for (size_t c = 0; c < 3; ++c) {
                const size_t k = 4 * i + c;
                sums[0] += direct[k];
                sums[1] += directTruth[k];
                sums[2] += bounce[k];
                sums[3] += bounceTruth.rgba[k];
                sums[4] += hdr[k] - direct[k] - bounce[k];
                sums[5] += skyTruth[k];
            }
            n += 3;
        }
        const double d = double(std::max<size_t>(n, 1));
        return Json{{"direct", sums[0] / d}, {"direct_reference", sums[1] / d},
                    {"bounce", sums[2] / d}, {"bounce_reference", sums[3] / d},
                    {"sky", sums[4] / d},    {"sky_reference", sums[5] / d}};
    };
    for (size_t m = 0; m < methods.size(); ++m) {
        Json entry = {{"label", methods[m].label},
                      {"settings", settingsJson(methods[m].settings)},
                      {"frames", logs[m].json()}};
        const double total = cli::median(timed(logs[m].totals));
        entry["frame_ms"] = total;
        entry["cost_relative"] = m == 0 ? 0.0 : (total - off) / off;
        Json passes = Json::object();
        for (const auto& [name, times] : logs[m].passes)
            passes[name] = cli::median(timed(times));
        entry["pass_ms"] = passes;

        // The converged image first: the one-frame figures compare each draw against it.
        progress.step(methods[m].label + ": converged");
        Scene cachedScene = withSettings(scene, methods[m].settings);
        cachedScene.settings.cache = true;
        Renderer still(ctx, cachedScene, RenderOptions{errorSize.width, errorSize.height, "final"});
        for (uint32_t f = 0; f < convergedFrames; ++f)
            still.renderFrame(scene.camera);
        const metrics::Image converged{errorSize.width, errorSize.height, still.readImage("hdr")};
        const metrics::Image convergedBounce =
            m > 0 ? bounceOf(still, bounceImage(cachedScene)) : metrics::Image{};

        // One uncached frame, kOneFrameDraws times with the patterns at successive places of
        // their sequence (a draw's figures vary with where its samples fall): the mean of each.
        progress.step(methods[m].label + ": one frame");
        Scene onceScene =
            withSettings(scene, methods[m].settings); // the renderer keeps a reference
        onceScene.settings.cache = false;
        std::map<std::string, double> sums;
        for (uint32_t draw = 0; draw < kOneFrameDraws; ++draw) {
            Renderer single(
                ctx, onceScene,
                RenderOptions{
                    errorSize.width, errorSize.height, "final", {bounceImage(onceScene)}, draw});
            single.renderFrame(scene.camera);
            if (geometry.empty()) {
                const std::vector<float> position = single.readImage("gbuffer.position");
                geometry.assign(position.size() / 4, 0);
                for (size_t i = 0; i < geometry.size(); ++i)
                    geometry[i] = position[4 * i + 3] != 0.0f;
                band = depthEdgeBand(position, errorSize.width, errorSize.height,
                                     scene.camera.position, 8);
                result["band_pixels"] = metrics::countInside(band);
            }
            const metrics::Image one{errorSize.width, errorSize.height, single.readImage("hdr")};
            sums["all"] += relMse(one, truth, geometry);
            sums["edge_band"] += relMse(one, truth, band);
            sums["vs_converged"] += relMse(one, converged, geometry);
            sums["vs_converged_band"] += relMse(one, converged, band);
            if (m > 0) {
                const metrics::Image oneBounce = bounceOf(single, bounceImage(onceScene));
                sums["bounce"] += relMse(oneBounce, bounceTruth, geometry);
                sums["bounce_band"] += relMse(oneBounce, bounceTruth, band);
                sums["bounce_vs_converged"] += relMse(oneBounce, convergedBounce, geometry);
            }
        }
        auto mean = [&](const char* key, const metrics::Mask& mask) {
            return Json{{"relmse", sums[key] / kOneFrameDraws},
                        {"pixels", metrics::countInside(mask)}};
        };
        entry["one_frame"] = {{"all", mean("all", geometry)},
                              {"edge_band", mean("edge_band", band)}};
        entry["converged"] = {{"all", figures(converged, truth, geometry)},
                              {"edge_band", figures(converged, truth, band)}};
        entry["one_frame_vs_converged"] = mean("vs_converged", geometry);
        entry["one_frame_vs_converged_band"] = mean("vs_converged_band", band);
        if (m > 0) {
            entry["bounce"] = {
                {"one_frame", mean("bounce", geometry)},
                {"one_frame_edge_band", mean("bounce_band", band)},
                // The bounce's own noise, free of the other cached effects' (shadow, AO).
                {"one_frame_vs_converged", mean("bounce_vs_converged", geometry)},
                {"converged", figures(convergedBounce, bounceTruth, geometry)},
                {"converged_edge_band", figures(convergedBounce, bounceTruth, band)}};
            entry["term_means"] = termMeans(still, cachedScene);
        }
        result["methods"].push_back(entry);
    }
    result["converged_frames"] = convergedFrames;
    result["one_frame_draws"] = kOneFrameDraws;
    result["reference_samples"] = reference.samples;
    progress.done();
    return result;
}

} // namespace ssgi::bench
