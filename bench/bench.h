// The benchmark program's parts: configurations of the methods, timed per pass on the device
// and compared with the path-traced reference; the ceiling probe; the cached series and
// walkthroughs. Each part returns JSON that bench/report.py turns into charts and tables.
#pragma once

#include "reference/integrator.h"
#include "renderer.h"
#include "scene/scene.h"
#include "vk/context.h"
#include "vk/pipeline.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace ssgi::bench {

using Json = nlohmann::json;
using PassTimes = std::map<std::string, double>; // pass name -> milliseconds

// What one benchmark run is asked to do.
struct Options {
    uint32_t width = 512, height = 512;           // timing size
    uint32_t errorWidth = 128, errorHeight = 128; // error size (real-time and reference)
    uint32_t warmup = 1, frames = 5;              // frames ignored, then frames timed
    uint32_t seriesFrames = 64;                   // cached still-camera frames
    // The references: their own relMSE is about the noise squared, 1e-4 at 1%, a tenth of the
    // least figure the bench reports (the bunny's, about 0.002).
    uint32_t referenceSpp = 16384;
    double referenceNoise = 0.01; // stop the reference sooner at this relative error
    bool error = true;            // the error renders (off: timing only)
    bool series = true;           // the cached still-camera series
    uint32_t seriesMethods = 3;   // the series' cache methods: 1 thesis rule, 2 + running mean,
                                  // 3 + running mean with cheap frames
    // Walkthrough: the configurations compared along the path (label, settings); empty: the
    // default ones (cache off, the thesis rule, the running mean with cheap frames).
    std::vector<std::pair<std::string, SettingOverrides>> methods;
};

// A progress bar on stderr (a line per step when stderr is not a terminal).
class Progress {
public:
    Progress(std::string title, size_t steps);
    void step(const std::string& label);
    void done();

private:
    double seconds() const;
    std::string title_;
    size_t steps_, done_ = 0;
    bool tty_;
    std::chrono::steady_clock::time_point start_;
};

// The scene with `overrides` applied over its own settings, each checked.
Scene withSettings(const Scene& scene, const SettingOverrides& overrides);
Json settingsJson(const SettingOverrides& settings);

// The last frame's pass timings.
PassTimes lastTimings(const Renderer& renderer);
double total(const PassTimes& times);

// Per-frame pass timings of one renderer, appended frame by frame, with the host's wall clock
// around each frame (on a CPU device it checks the sum of the passes' timestamps).
struct FrameLog {
    std::map<std::string, std::vector<double>> passes;
    std::vector<double> totals, walls;

    void add(const Renderer& renderer, double wallMs);
    Json json() const;
};

// Renders `frames` frames with one renderer per scene, taking the renderers in turn frame by
// frame, so that whatever else loads the machine (on lavapipe GPU time is CPU time) weighs on
// every configuration alike. `after(i, frame, renderer, wall ms)` follows each frame.
using AfterFrame = std::function<void(size_t, uint32_t, Renderer&, double)>;
void interleaved(vk::Context& ctx, const std::vector<Scene>& scenes, VkExtent2D size,
                 uint32_t frames, const std::function<Camera(uint32_t)>& cameraOf,
                 const AfterFrame& after, Progress* progress = nullptr,
                 const std::string& what = "");

// The reference (full mode: direct, one bounce, sky) of `camera`, cached by content.
struct Reference {
    std::vector<float> rgba;
    uint32_t samples = 0;
    double noise = 0.0;
};
Reference fullReference(const Scene& scene, const Camera& camera, const Options& options);
// The same for one of the reference's other modes (the bounce alone, the direct light, the sky).
Reference modeReference(const Scene& scene, const Camera& camera, const Options& options,
                        reference::Mode mode);
// relMSE and SSIM of the renderer's "hdr" against the reference over the pixels with geometry.
struct Error {
    double relMse = 0.0, ssim = 0.0;
};
Error hdrError(Renderer& renderer, const Reference& reference);

// The device and driver, for every result file.
Json deviceJson(const vk::Context& ctx);
// Every image of the frame graph with its bytes.
Json memoryJson(const Renderer& renderer);

// Texel fetches and bytes the device moves per millisecond in trivial kernels, sampled in
// every round of timed frames so that it sees the same load as the passes.
class CeilingProbe {
public:
    CeilingProbe(vk::Context& ctx, VkExtent2D target);
    ~CeilingProbe();
    void sample();                // times each kernel once
    Json json(size_t skip) const; // medians over the samples after the first `skip`

private:
    struct Kernel;
    vk::Context& ctx_;
    VkExtent2D target_;
    std::vector<vk::Pipeline> pipelines_;
    VkSampler sampler_ = VK_NULL_HANDLE;
    std::vector<std::unique_ptr<Kernel>> kernels_;
};

// Configurations timed per pass (cache off) and, with options.error, compared with the
// reference; the still-camera cached series. See sweep.cpp.
Json sweep(vk::Context& ctx, const Scene& scene, const Options& options);

// Cached still-camera series: per-frame pass timings and error, one per cache method.
Json cachedSeries(vk::Context& ctx, const Scene& scene, const Options& options,
                  const Reference& reference, Progress& progress);
size_t cachedSeriesSteps(const Options& options);

// The scene's camera path with the cache off and on: per-frame pass timings, and the error
// at `errorFrames` frames along the path.
Json walkthrough(vk::Context& ctx, const Scene& scene, const Options& options, uint32_t pathFrames,
                 uint32_t errorFrames);

// The cache's fixes for where it failed (automatic cut, thin geometry, screen edge, the bounce
// computed anew while the camera moves), each turned off alone, and the guard band turned on,
// beside the default and the cache off: per-frame timings and error along the camera path
// ("walkthrough", as above) and on a still camera at the path's end for `stillFrames` frames
// ("still", its error at the last). See series.cpp cacheFixMethods.
Json cacheFixes(vk::Context& ctx, const Scene& scene, const Options& options, uint32_t pathFrames,
                uint32_t errorFrames, uint32_t stillFrames);

// The indirect light's methods (off, the thesis's, the interleaved one, or options.methods):
// their cost relative to the rest of an uncached frame, and their error one frame and after
// `convergedFrames` cached frames, over the image and around depth edges. See indirect.cpp.
Json indirectComparison(vk::Context& ctx, const Scene& scene, const Options& options,
                        uint32_t convergedFrames);

} // namespace ssgi::bench
