// Scene units do not matter: the Cornell box from 1e-9 to 1e9 units, its light scaled to match
// (test::scaledScene), gives the image it gives at scale 1, in the real-time renderer and in the
// path-traced reference alike. Validation and synchronization validation are on.
#include "metrics/metrics.h"
#include "reference/render.h"
#include "renderer.h"
#include "support.h"

#include <cstdio>

using namespace ssgi;
using namespace ssgi::reference;

namespace {

class SceneUnitsTest : public test::VulkanTest {};

ReferenceOptions fullOptions(uint32_t size, uint32_t spp) {
    ReferenceOptions o;
    o.mode = Mode::Full;
    o.width = o.height = size;
    o.spp = spp;
    return o;
}

} // namespace

// The Cornell box from 1e-9 to 1e9 units gives the image it gives at 1, within relMSE 0.01:
// the floors on the depths and distances the shaders divide by are relative to the scene's size
// (absolute ones broke the bounce and the penumbrae at small scales).
TEST_F(SceneUnitsTest, TheCornellBoxIsTheSameAtAnyScale) {
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    scene.settings.indirect_method = 1; // the bounce the bound below was measured with
    const auto image = [&](float k) {
        const test::Frame f = test::render(test::scaledScene(scene, k), 64, 64);
        return metrics::Image{f.width, f.height, f.hdr};
    };
    const metrics::Image unit = image(1.0f);
    for (float k : test::kSceneScales) {
        const metrics::Image scaled = image(k);
        const double relMse = metrics::errorFigures(scaled, unit, {}, {}).relMse;
        std::printf("Cornell box at scale %g: relMSE %.3g against scale 1\n", k, relMse);
        EXPECT_LT(relMse, 1e-4) << "scale " << k; // measured at most 3.2e-6 (1e5)
    }
}

// The Cornell box from 1e-9 to 1e9 units gives the image it gives at 1, sample for sample (the
// same seed draws the same paths). Embree's robust intersector drops the barycentrics of hits
// on triangles under about 1e-9 units across, which put every hit at 1e-9 at a vertex (1.13).
TEST(Reference, TheCornellBoxIsTheSameAtAnyScale) {
    const Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    const auto image = [&](float k) {
        const Scene scaled = test::scaledScene(scene, k);
        const ReferenceImage r = renderReference(scaled, scaled.camera, fullOptions(32, 16));
        EXPECT_EQ(r.nonFiniteSamples, 0u) << "scale " << k;
        return metrics::Image{r.width, r.height, r.rgba};
    };
    const metrics::Image unit = image(1.0f);
    for (float k : test::kSceneScales) {
        const double relMse = metrics::errorFigures(image(k), unit, {}, {}).relMse;
        std::printf("Cornell box at scale %g: relMSE %.3g against scale 1\n", k, relMse);
        EXPECT_LT(relMse, 1e-6) << "scale " << k; // measured at most 3.3e-10 (1e3)
    }
}
