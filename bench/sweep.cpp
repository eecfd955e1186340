// The configuration sweep of one scene: the rows of the timing plan (configs.h) rendered with
// their frames interleaved round by round and the ceiling probe sampled once a round, so that
// the machine's load weighs on all of them alike; every configuration's error from its own
// render at the error size against the path-traced reference; the cached still-camera series;
// the memory of the frame. The rows' frames go out whole: bench/analysis.py composes each
// configuration's time from them.
#include "configs.h"

namespace ssgi::bench {

Json sweep(vk::Context& ctx, const Scene& scene, const Options& options) {
    const std::vector<Axis> axes = makeAxes();
    const std::vector<Config> configs = makeConfigs(axes);
    const TimingPlan plan = makeTimingPlan(axes);
    const size_t steps = options.warmup + options.frames + 1 +
                         (options.error ? 1 + configs.size() : 0) +
                         (options.series ? cachedSeriesSteps(options) : 0);
    Progress progress(std::string("  ") + scene.sourcePath, steps);
    Json result;
    CeilingProbe probe(ctx, {options.width, options.height});

    std::vector<Scene> scenes;
    for (const Index& index : plan.rows)
        scenes.push_back(withSettings(scene, settingsOf(axes, index)));
    std::vector<FrameLog> logs(plan.rows.size());
    interleaved(
        ctx, scenes, {options.width, options.height}, options.warmup + options.frames,
        [&](uint32_t) { return scene.camera; },
        [&](size_t i, uint32_t f, Renderer& renderer, double wall) {
            logs[i].add(renderer, wall);
            if (i + 1 == scenes.size()) probe.sample(); // once a round, after every renderer
            if (i == 0 && f == 0) {
                // The share of pixels with geometry: the passes skip the others.
                const std::vector<float> position = renderer.readImage("gbuffer.position");
                size_t geometry = 0;
                for (size_t k = 3; k < position.size(); k += 4)
                    geometry += position[k] != 0.0f;
                result["geometry_fraction"] = double(geometry) / double(position.size() / 4);
            }
        },
        &progress, "timing " + std::to_string(plan.rows.size()) + " configurations");
    result["probe"] = probe.json(options.warmup);
    for (size_t r = 0; r < plan.rows.size(); ++r) {
        Json row = logs[r].json(); // every frame, the warm-up included
        row["label"] = labelOf(axes, plan.rows[r]);
        row["index"] = plan.rows[r];
        row["settings"] = settingsJson(settingsOf(axes, plan.rows[r]));
        result["rows"].push_back(row);
    }
    for (size_t a = 0; a < axes.size(); ++a)
        result["row_of"][axes[a].name] = plan.rowOf[a];
    result["check_row"] = plan.check;
    for (const Axis& axis : axes) {
        Json values = Json::array();
        for (const AxisValue& v : axis.values)
            values.push_back({{"label", v.label}, {"settings", settingsJson(v.settings)}});
        result["axes"].push_back(
            {{"name", axis.name}, {"passes", axis.passes}, {"values", values}});
    }

    Reference reference;
    if (options.error) {
        progress.step("reference (path tracer, cached by content)");
        reference = fullReference(scene, scene.camera, options);
        result["reference"] = {{"mode", "full"},
                               {"width", options.errorWidth},
                               {"height", options.errorHeight},
                               {"samples", reference.samples},
                               {"noise", reference.noise}};
    }
    for (const Config& c : configs) {
        Json j = {{"label", labelOf(axes, c.index)},
                  {"group", c.group},
                  {"index", c.index},
                  {"settings", settingsJson(settingsOf(axes, c.index))}};
        if (options.error) {
            progress.step("error: " + labelOf(axes, c.index));
            const Scene s = withSettings(scene, settingsOf(axes, c.index));
            Renderer renderer(ctx, s, {options.errorWidth, options.errorHeight, "final"});
            renderer.renderFrame(scene.camera);
            const Error e = hdrError(renderer, reference);
            j["rel_mse"] = e.relMse;
            j["ssim"] = e.ssim;
        }
        result["configs"].push_back(j);
    }
    if (options.series) result["series"] = cachedSeries(ctx, scene, options, reference, progress);

    // Memory of the default frame with the cache on (every history), here and at 720p and 1080p;
    // images are allocated, the transient ones placed in their shared block, when the renderer
    // is built, so no frame is needed.
    progress.step("memory");
    const Scene cached = withSettings(scene, {{"cache", 1}});
    for (VkExtent2D size : {VkExtent2D{options.width, options.height}, VkExtent2D{1280, 720},
                            VkExtent2D{1920, 1080}}) {
        Renderer renderer(ctx, cached, {size.width, size.height, "final"});
        result["memory"][std::to_string(size.width) + "x" + std::to_string(size.height)] =
            memoryJson(renderer);
    }
    progress.done();
    return result;
}

} // namespace ssgi::bench
