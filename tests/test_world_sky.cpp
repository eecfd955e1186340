// The sky's visibility held in the world cache's cells (world_sky_visibility,
// world_sky_visibility.comp): the lookup's value stands close to the per-pixel pass's, which it
// replaces, at full and at half resolution.
#include "renderer.h"
#include "support.h"

#include <algorithm>
#include <cmath>

using namespace ssgi;

namespace {

constexpr uint32_t kSize = 64;

// How two images of the sky's visibility compare over the pixels that hold a surface: the mean
// absolute difference (over rgb), the mean of each, and the darkest value of the first.
struct SkyComparison {
    double meanDifference = 0.0, meanA = 0.0, meanB = 0.0, darkestA = 1.0;
};

SkyComparison compareSky(const std::vector<float>& a, const std::vector<float>& b,
                         const std::vector<float>& position) {
    SkyComparison c;
    size_t covered = 0;
    for (size_t i = 0; i < position.size() / 4; ++i) {
        if (position[4 * i + 3] == 0.0f) continue;
        ++covered;
        for (int k = 0; k < 3; ++k) {
            c.meanDifference += std::abs(double(a[4 * i + k]) - double(b[4 * i + k]));
            c.meanA += a[4 * i + k];
            c.meanB += b[4 * i + k];
            c.darkestA = std::min(c.darkestA, double(a[4 * i + k]));
        }
    }
    const double n = 3.0 * double(std::max<size_t>(covered, 1));
    c.meanDifference /= n;
    c.meanA /= n;
    c.meanB /= n;
    std::printf("%zu pixels: mean %.4f against %.4f, mean difference %.4f, darkest %.3f\n", covered,
                c.meanA, c.meanB, c.meanDifference, c.darkestA);
    return c;
}

class WorldSkyTest : public test::VulkanTest {
protected:
    // Sponza: arcades and a roofless court, whose floor, walls and galleries see from all of
    // the sky to little of it.
    Scene scene = [] {
        Scene s = loadScene(test::sourcePath("scenes/sponza.json"));
        s.settings.cache = false;
        s.settings.world_sky_visibility = true;
        return s;
    }();
    Scene perPixel = [this] {
        Scene s = scene;
        s.settings.world_sky_visibility = false;
        return s;
    }();
};

// One uncached frame: the cells' sky visibility, interpolated between cells, against the
// per-pixel pass's at the same camera, which looks along Sponza's gallery (0 to 1, 0.048 on
// average). The two differ by 7% of that mean per pixel (measured), the cells' value being the
// one at a point of each cell rather than at the pixel's own, and their means by 0.6%.
TEST_F(WorldSkyTest, TheCellsHoldWhatThePixelsCompute) {
    ASSERT_TRUE(skyInWorldCache(scene));
    ASSERT_FALSE(skyInWorldCache(perPixel));
    Renderer cells(test::context(), scene,
                   {kSize, kSize, "final", {"world.sky_visibility", "gbuffer.position"}});
    Renderer pixels(test::context(), perPixel, {kSize, kSize, "final", {"sky_visibility"}});
    cells.renderFrame(scene.camera);
    pixels.renderFrame(scene.camera);
    // The per-pixel pass is not made where the cells hold the term.
    for (const PassTiming& t : cells.lastFrameProfile().passes)
        EXPECT_NE(t.name, "sky_visibility");
    const SkyComparison c =
        compareSky(cells.readImage("world.sky_visibility"), pixels.readImage("sky_visibility"),
                   cells.readImage("gbuffer.position"));
    EXPECT_LT(c.darkestA, 0.3) << "no occluded surface in view: nothing was compared";
    EXPECT_LT(c.meanDifference, 0.12 * c.meanB);
    EXPECT_NEAR(c.meanA, c.meanB, 0.04 * c.meanB);
}

// With world_half_res the sky's visibility is upsampled from the same samples as the bounce, and
// looked up alone where the bounce is: close to the full-resolution lookup's (10% of the mean per
// pixel, 0.4% in the mean, measured).
TEST_F(WorldSkyTest, HalfResolutionLookupKeepsTheFullOnesSky) {
    Scene halfScene = scene;
    halfScene.settings.world_half_res = true;
    Renderer full(test::context(), scene,
                  {kSize, kSize, "final", {"world.sky_visibility", "gbuffer.position"}});
    Renderer half(test::context(), halfScene, {kSize, kSize, "final", {"world.sky_visibility"}});
    full.renderFrame(scene.camera);
    half.renderFrame(scene.camera);
    const SkyComparison c =
        compareSky(half.readImage("world.sky_visibility"), full.readImage("world.sky_visibility"),
                   full.readImage("gbuffer.position"));
    EXPECT_LT(c.meanDifference, 0.15 * c.meanB);
    EXPECT_NEAR(c.meanA, c.meanB, 0.03 * c.meanB);
}

} // namespace
