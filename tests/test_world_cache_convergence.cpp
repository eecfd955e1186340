// The world cache's bounce (indirect_method 3) converges as its samples grow: more VPLs a cell
// (world_vpls) or more frames of them (world_new_cell_frames, the frames' worth a cell of an
// uncached frame gathers, with world_frames at its most) bring one uncached frame's bounce nearer
// the path tracer's, never further, over each setting's whole range. lavapipe stops an
// invocation's loops after 65,535 iterations in all, and a gather that lost the rest of its
// samples there grew darker with every sample added (world_gather.comp).
#include "metrics/metrics.h"
#include "reference/cache.h"
#include "renderer.h"
#include "support.h"

#include <cstdio>
#include <vector>

using namespace ssgi;

namespace {

constexpr uint32_t kSize = 32;

// The bounce as outgoing radiance (irradiance / pi times the albedo), as the reference's
// indirect mode gives it, and the pixels that hold geometry.
struct Bounce {
    std::vector<float> radiance;
    metrics::Mask geometry;
};

// The bounce of the last of `frames` frames of a still camera, with the cache or without.
Bounce worldBounce(Scene scene, const SettingOverrides& settings, bool cache = false,
                   int frames = 1) {
    scene.settings.indirect_method = 3;
    scene.settings.cache = cache;
    scene.settings = withOverrides(scene.settings, settings, "test");
    Renderer renderer(test::context(), scene, {kSize, kSize, "final"});
    for (int f = 0; f < frames; ++f)
        renderer.renderFrame(scene.camera);
    Bounce b;
    b.radiance = renderer.readImage("world.indirect");
    const std::vector<float> albedo = renderer.readImage("gbuffer.albedo");
    const std::vector<float> position = renderer.readImage("gbuffer.position");
    for (size_t i = 0; i < b.radiance.size(); ++i)
        if (i % 4 != 3) b.radiance[i] *= albedo[i];
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i)
        b.geometry.push_back(position[4 * i + 3] != 0.0f);
    return b;
}

double relMse(const Bounce& b, const std::vector<float>& truth) {
    metrics::Image a{kSize, kSize, b.radiance}, t{kSize, kSize, truth};
    return metrics::errorFigures(a, t, b.geometry, metrics::ssimMap(a, t)).relMse;
}

double mean(const Bounce& b) {
    double sum = 0.0;
    for (size_t i = 0; i < b.radiance.size(); ++i)
        if (i % 4 != 3) sum += b.radiance[i];
    return sum / double(b.radiance.size() / 4 * 3);
}

// Along `values` of one setting, the relMSE against the path tracer's bounce never rises by more
// than 10% of the smallest so far (the estimate's own noise between sample counts), and the
// bounce's mean stays within 5% of the first one's: a gather that loses samples darkens.
std::vector<float> truthBounce(const Scene& scene) {
    reference::ReferenceOptions options;
    options.width = options.height = kSize;
    options.spp = 1024;
    options.mode = reference::Mode::Indirect;
    return reference::cachedReference(scene, options).rgba;
}

void expectConverges(const char* sceneFile, const char* setting, const std::vector<int>& values,
                     const SettingOverrides& others = {}) {
    const Scene scene = loadScene(test::sourcePath(sceneFile));
    const std::vector<float> truth = truthBounce(scene);
    double best = 0.0, firstMean = 0.0;
    for (size_t k = 0; k < values.size(); ++k) {
        SettingOverrides settings = others;
        settings[setting] = double(values[k]);
        const Bounce b = worldBounce(scene, settings);
        const double error = relMse(b, truth), m = mean(b);
        std::printf("%s %s=%d: relMSE %.5f, mean %.5f\n", sceneFile, setting, values[k], error, m);
        if (k == 0) {
            best = error;
            firstMean = m;
            continue;
        }
        EXPECT_LE(error, best * 1.1) << setting << "=" << values[k];
        EXPECT_NEAR(m, firstMean, 0.05 * firstMean) << setting << "=" << values[k];
        best = std::min(best, error);
    }
}

TEST(WorldCacheConvergence, MoreVplsBringTheCornellBoxNearer) {
    expectConverges("scenes/cornell-box.json", "world_vpls", {48, 192, 1024});
}

TEST(WorldCacheConvergence, MoreFramesBringTheCornellBoxNearer) {
    expectConverges("scenes/cornell-box.json", "world_new_cell_frames", {16, 64, 512},
                    {{"world_frames", 512.0}});
}

TEST(WorldCacheConvergence, MoreVplsBringSponzaNearer) {
    expectConverges("scenes/sponza.json", "world_vpls", {48, 192, 1024});
}

TEST(WorldCacheConvergence, MoreFramesBringSponzaNearer) {
    expectConverges("scenes/sponza.json", "world_new_cell_frames", {16, 64, 512},
                    {{"world_frames", 512.0}});
}

// A still camera's cells, refreshed one frame's worth at a time up to world_frames, come nearer
// the path tracer's bounce than one uncached frame's (world_new_cell_frames at once): a refresh
// is an unbiased estimate like the first gather. (With the disk's samples at the same radii in
// every refresh, the Cornell box's image settled at 0.0053 against one uncached frame's 0.0034.)
TEST(WorldCacheConvergence, RefreshesBringAStillCameraNearer) {
    for (const char* file : {"scenes/cornell-box.json", "scenes/sponza.json"}) {
        const Scene scene = loadScene(test::sourcePath(file));
        const std::vector<float> truth = truthBounce(scene);
        const double uncached = relMse(worldBounce(scene, {}), truth);
        const Bounce settled = worldBounce(scene, {}, true, 24);
        const double cached = relMse(settled, truth);
        std::printf("%s: one uncached frame %.5f, 24 cached frames %.5f\n", file, uncached, cached);
        EXPECT_LT(cached, uncached) << file;
    }
}

} // namespace
