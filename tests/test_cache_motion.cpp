// The temporal cache under a moving camera: every frame the history is resampled bilinearly at
// the reprojected point, which blurs it a little (the reason for the thesis's tiled refresh).
// Each history value carries the blur it has gathered, and an effect's budget bounds it: the
// history's weight is cut where it would exceed the budget, and the pixel is computed again.
#include "renderer.h"
#include "support.h"

#include <algorithm>
#include <cmath>

using namespace ssgi;

namespace {

class CacheMotionTest : public test::VulkanTest {
protected:
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    static constexpr uint32_t kSize = 96;

    // The camera `frame` steps along a slow pan: about a third of a pixel a frame sideways.
    Camera panned(int frame) const {
        Camera c = scene.camera;
        c.position.x += 0.0025f * float(frame);
        return c;
    }

    // The shadow term after `frames` frames of the pan (and the G-buffer's positions).
    std::vector<float> shadowAfterPan(const Scene& s, int frames,
                                      std::vector<float>* position = nullptr) {
        Renderer renderer(test::context(), s, {kSize, kSize, "final"});
        for (int f = 0; f < frames; ++f)
            renderer.renderFrame(panned(f));
        if (position) *position = renderer.readImage("gbuffer.position");
        return renderer.readImage(s.settings.cache ? "shadow.history" : "shadow");
    }
};

double rmse(const std::vector<float>& a, const std::vector<float>& b,
            const std::vector<float>& position) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < a.size() / 4; ++i) {
        if (position[4 * i + 3] == 0.0f) continue;
        sum += (a[4 * i] - b[4 * i]) * (a[4 * i] - b[4 * i]);
        ++n;
    }
    return std::sqrt(sum / double(std::max<size_t>(n, 1)));
}

// Along the pan, no history value carries more blur than its effect's budget, one frame of
// resampling aside (at most half a squared pixel); on a still camera none gathers any.
TEST_F(CacheMotionTest, HistoriesCarryNoMoreBlurThanTheirBudget) {
    scene.settings.cache_blur_ao = 1.0;
    scene.settings.indirect_method = 1; // the screen-space bounce, whose history has a budget
    scene.settings.cache_blur_indirect = 2.0;
    Renderer renderer(test::context(), scene, {kSize, kSize, "final"});
    const std::vector<float> position = [&] {
        for (int f = 0; f < 48; ++f)
            renderer.renderFrame(panned(f));
        return renderer.readImage("gbuffer.position");
    }();
    for (auto [history, budget] :
         {std::pair{"shadow.history", 0.0}, {"ao.history", 1.0}, {"indirect.history", 2.0}}) {
        const std::vector<float> value = renderer.readImage(history);
        float most = 0.0f, mean = 0.0f;
        size_t n = 0;
        for (size_t i = 0; i < value.size() / 4; ++i)
            if (position[4 * i + 3] != 0.0f) {
                most = std::max(most, value[4 * i + 3]);
                mean += value[4 * i + 3];
                ++n;
            }
        std::printf("%s after a 48-frame pan: blur at most %.3f px^2, mean %.3f (budget %.1f)\n",
                    history, most, mean / float(n), budget);
        EXPECT_LE(most, budget + 0.5 + 1e-3) << history;
        if (budget > 0.0) {
            EXPECT_GT(mean / float(n), 0.05) << history << ": the pan resamples";
        }
    }
    Renderer still(test::context(), scene, {kSize, kSize, "final"});
    for (int f = 0; f < 48; ++f)
        still.renderFrame(scene.camera);
    const std::vector<float> ao = still.readImage("ao.history");
    for (size_t i = 0; i < ao.size() / 4; ++i)
        ASSERT_EQ(ao[4 * i + 3], 0.0f) << "a still camera resamples at texel centres: no blur";
}

// The shadow term is sharp, so its budget is none: along a pan the cached shadow is computed
// anew every frame and stays close to the uncached one (they differ by the cached pattern's
// moving radial offset), while an unbounded history drifts away from it (blurred edges).
// Measured at 96x96: unbounded 0.0677, budget 0 0.0065.
TEST_F(CacheMotionTest, ABlurBudgetKeepsAPannedShadowSharp) {
    scene.settings.indirect = false;
    scene.settings.ao = false;
    const int frames = 40;
    std::vector<float> position;
    Scene fresh = scene;
    fresh.settings.cache = false;
    const std::vector<float> truth = shadowAfterPan(fresh, frames, &position);
    Scene unbounded = scene;
    unbounded.settings.cache_blur_shadow = 1e6;
    unbounded.settings.cache_method = 1;
    const double unboundedError = rmse(shadowAfterPan(unbounded, frames), truth, position);
    Scene bounded = unbounded;
    bounded.settings.cache_blur_shadow = 0.0;
    const double boundedError = rmse(shadowAfterPan(bounded, frames), truth, position);
    std::printf("shadow RMSE to a fresh shadow after a %d-frame pan: unbounded %.4f, budget 0 "
                "%.4f\n",
                frames, unboundedError, boundedError);
    EXPECT_LT(boundedError, 0.5 * unboundedError);
}

} // namespace
