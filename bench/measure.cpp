// What every part of the benchmark shares: progress, settings, per-pass medians, the reference
// and the error against it, the device and the memory of a frame.
#include "bench.h"

#include "app/cli.h"
#include "metrics/metrics.h"
#include "reference/cache.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <unistd.h>

namespace ssgi::bench {

Progress::Progress(std::string title, size_t steps)
    : title_(std::move(title)), steps_(steps), tty_(isatty(2)),
      start_(std::chrono::steady_clock::now()) {}

double Progress::seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::step(const std::string& label) {
    ++done_;
    const size_t width = 30, filled = steps_ ? width * std::min(done_, steps_) / steps_ : width;
    const std::string bar = std::string(filled, '#') + std::string(width - filled, '.');
    // The label names what starts now, so a slow step shows what is being waited for.
    std::fprintf(stderr, "%s%s [%s] %zu/%zu %4.0f s  %s%s", tty_ ? "\r\033[K" : "", title_.c_str(),
                 bar.c_str(), done_, steps_, seconds(), label.c_str(), tty_ ? "" : "\n");
    std::fflush(stderr);
}

void Progress::done() {
    std::fprintf(stderr, "%s%s done: %zu steps in %.0f s\n", tty_ ? "\r\033[K" : "", title_.c_str(),
                 done_, seconds());
}

Scene withSettings(const Scene& scene, const SettingOverrides& overrides) {
    Scene s = scene;
    s.settings = withOverrides(s.settings, overrides, "benchmark");
    return s;
}

Json settingsJson(const SettingOverrides& settings) {
    Json j = Json::object();
    for (const auto& [key, value] : settings)
        j[key] = value;
    return j;
}

PassTimes lastTimings(const Renderer& renderer) {
    PassTimes times;
    for (const auto& timing : renderer.timings())
        times[timing.name] = timing.milliseconds;
    return times;
}

double total(const PassTimes& times) {
    double sum = 0.0;
    for (const auto& [name, ms] : times)
        sum += ms;
    return sum;
}

void FrameLog::add(const Renderer& renderer, double wallMs) {
    const PassTimes times = lastTimings(renderer);
    for (const auto& [name, ms] : times)
        passes[name].push_back(ms);
    totals.push_back(total(times));
    walls.push_back(wallMs);
}

Json FrameLog::json() const {
    return {{"passes", passes}, {"total_ms", totals}, {"wall_ms", walls}};
}

void interleaved(vk::Context& ctx, const std::vector<Scene>& scenes, VkExtent2D size,
                 uint32_t frames, const std::function<Camera(uint32_t)>& cameraOf,
                 const AfterFrame& after, Progress* progress, const std::string& what) {
    std::vector<std::unique_ptr<Renderer>> renderers;
    for (const Scene& s : scenes)
        renderers.push_back(
            std::make_unique<Renderer>(ctx, s, RenderOptions{size.width, size.height, "final"}));
    for (uint32_t f = 0; f < frames; ++f) {
        if (progress)
            progress->step(what + ": frame " + std::to_string(f + 1) + "/" +
                           std::to_string(frames) + " of " + std::to_string(scenes.size()));
        for (size_t i = 0; i < renderers.size(); ++i) {
            const auto start = std::chrono::steady_clock::now();
            renderers[i]->renderFrame(cameraOf(f));
            const std::chrono::duration<double, std::milli> wall =
                std::chrono::steady_clock::now() - start;
            after(i, f, *renderers[i], wall.count());
        }
    }
}

Reference fullReference(const Scene& scene, const Camera& camera, const Options& options) {
    return modeReference(scene, camera, options, reference::Mode::Full);
}

Reference modeReference(const Scene& scene, const Camera& camera, const Options& options,
                        reference::Mode mode) {
    reference::ReferenceOptions ro;
    ro.mode = mode;
    ro.width = options.errorWidth;
    ro.height = options.errorHeight;
    ro.spp = options.referenceSpp;
    ro.noiseTarget = options.referenceNoise;
    // Pixel-centre samples, as the G-buffer takes them, so that edges agree pixel for pixel.
    ro.jitter = false;
    const reference::ReferenceImage image = reference::cachedReference(scene, camera, ro);
    return {image.rgba, image.samples, image.noise};
}

Error hdrError(Renderer& renderer, const Reference& reference) {
    const VkExtent2D size = renderer.size();
    const std::vector<float> position = renderer.readImage("gbuffer.position");
    metrics::Mask geometry(size_t(size.width) * size.height);
    for (size_t i = 0; i < geometry.size(); ++i)
        geometry[i] = position[4 * i + 3] != 0.0f;
    const metrics::Image test{size.width, size.height, renderer.readImage("hdr")};
    const metrics::Image truth{size.width, size.height, reference.rgba};
    const metrics::Figures f =
        metrics::errorFigures(test, truth, geometry, metrics::ssimMap(test, truth));
    return {f.relMse, f.ssim};
}

Json deviceJson(const vk::Context& ctx) {
    const VkPhysicalDeviceProperties& p = ctx.properties;
    return {{"name", p.deviceName},
            {"driver", ctx.driverName},
            {"api", std::to_string(VK_API_VERSION_MAJOR(p.apiVersion)) + "." +
                        std::to_string(VK_API_VERSION_MINOR(p.apiVersion)) + "." +
                        std::to_string(VK_API_VERSION_PATCH(p.apiVersion))},
            {"cpu_device", p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU}};
}

Json memoryJson(const Renderer& renderer) {
    const graph::FrameGraph& graph = renderer.frameGraph();
    const graph::FrameGraph::SharedMemory shared = graph.sharedMemory();
    Json list = Json::array();
    for (const auto& [name, bytes, pair] : graph.imageMemory()) {
        const bool inBlock =
            std::find(shared.images.begin(), shared.images.end(), name) != shared.images.end();
        list.push_back({{"image", name}, {"bytes", bytes}, {"shared", inBlock}, {"history", pair}});
    }
    // The transient images' one block: with the images not in it, what the graph holds.
    list.push_back({{"image", "shared block"}, {"bytes", shared.bytes}, {"block", true}});
    return list;
}

} // namespace ssgi::bench
