// The guard band (setting guard_band): the screen images are rendered that many pixels
// beyond each edge of the output, so the screen-space effects see what lies just off screen,
// while the output keeps its size and every pixel of it the ray it had without a band.
#include "metrics/metrics.h"
#include "reference/render.h"
#include "renderer.h"
#include "scene/camera.h"
#include "support.h"

#include <cmath>

using namespace ssgi;

namespace {

class GuardBandTest : public test::VulkanTest {
protected:
    static constexpr uint32_t kWidth = 96, kHeight = 72; // the stability suite's --quick size

    // `frames` frames from a still `camera` (one: uncached), with a band of `band` pixels.
    static std::unique_ptr<Renderer> rendered(Scene scene, const Camera& camera, int band,
                                              int frames = 1) {
        scene.settings.cache = frames > 1;
        scene.settings.guard_band = band;
        auto r = std::make_unique<Renderer>(test::context(), scene, RenderOptions{kWidth, kHeight});
        for (int i = 0; i < frames; ++i)
            r->renderFrame(camera);
        return r;
    }
};

TEST_F(GuardBandTest, TheOutputKeepsItsSizeAndItsPixelsRays) {
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    scene.settings.indirect_method = 1; // the screen-space bounce: its "indirect" image is read
    std::unique_ptr<Renderer> plain = rendered(scene, scene.camera, 0);
    std::unique_ptr<Renderer> banded = rendered(scene, scene.camera, 20);
    EXPECT_EQ(banded->size().width, kWidth);
    EXPECT_EQ(banded->size().height, kHeight);
    EXPECT_EQ(banded->frameGraph().image(banded->frameGraph().find("gbuffer.normal")).extent.width,
              kWidth + 40)
        << "the screen images hold the band";
    EXPECT_EQ(banded->frameGraph().image(banded->frameGraph().find("ldr")).extent.width, kWidth)
        << "the output does not";

    // The same surface point behind every pixel: the G-buffer's positions agree to float
    // precision (the box is about 0.55 m across).
    const std::vector<float> a = plain->readImage("gbuffer.position");
    const std::vector<float> b = banded->readImage("gbuffer.position");
    ASSERT_EQ(a.size(), b.size());
    float largest = 0.0f;
    for (size_t i = 0; i < a.size(); i += 4) {
        ASSERT_EQ(a[i + 3], b[i + 3]) << "geometry at one pixel and not the other: " << i / 4;
        for (int c = 0; c < 3; ++c)
            largest = std::max(largest, std::abs(a[i + c] - b[i + c]));
    }
    EXPECT_LT(largest, 1e-4f);
    for (const char* name : {"hdr", "ldr", "ao", "shadow", "indirect"})
        EXPECT_EQ(banded->readImage(name).size(), size_t(kWidth) * kHeight * 4) << name;
}

// The stability suite's screen-edge case at the end of its camera path: the pillar has just
// left the screen on the left, and the floor and wall it occludes are still on it. Against the
// path-traced AO, a band of 32 pixels takes at least a fifth off the error of the AO converged
// over 40 still frames in the columns nearest the pillar (measured: 0.046 -> 0.025), and leaves
// the far half of the image as it was. Without the sky's visibility, so that the AO reaches as
// far as it does when it stands for all of the sky's occlusion (aoRadius: 5% of the diagonal).
TEST_F(GuardBandTest, TheAoSeesAnOccluderJustOffScreen) {
    Scene scene = loadScene(test::sourcePath("scenes/stability/screen-edge.json"));
    scene.settings.sky_visibility = false;
    const Camera camera = cameraAt(scene.cameraPath, scene.cameraPath.keys.back().time);
    std::unique_ptr<Renderer> plain = rendered(scene, camera, 0, 40);
    std::unique_ptr<Renderer> banded = rendered(scene, camera, 32, 40);

    reference::ReferenceOptions ro;
    ro.mode = reference::Mode::Ao;
    ro.width = kWidth;
    ro.height = kHeight;
    ro.spp = 256;
    const reference::ReferenceImage truth = reference::renderReference(scene, camera, ro);

    const std::vector<float> position = plain->readImage("gbuffer.position");
    metrics::Mask nearEdge(size_t(kWidth) * kHeight), farSide(nearEdge.size());
    for (size_t i = 0; i < nearEdge.size(); ++i) {
        if (position[4 * i + 3] == 0.0f) continue;
        nearEdge[i] = i % kWidth < 12;
        farSide[i] = i % kWidth >= kWidth / 2;
    }
    const metrics::Image reference{kWidth, kHeight, truth.rgba};
    auto error = [&](Renderer& r, const metrics::Mask& mask) {
        const metrics::Image ao{kWidth, kHeight, r.readImage("ao.history")};
        return metrics::errorFigures(ao, reference, mask, std::vector<double>(ao.pixels(), 0.0))
            .relMse;
    };
    const double without = error(*plain, nearEdge), with = error(*banded, nearEdge);
    std::printf("AO relMSE in the 12 columns nearest the pillar: %.4f without a band, %.4f with\n",
                without, with);
    EXPECT_LT(with, 0.8 * without);
    const double farWithout = error(*plain, farSide), farWith = error(*banded, farSide);
    std::printf("and on the far half: %.4f, %.4f\n", farWithout, farWith);
    EXPECT_LT(std::abs(farWith - farWithout), 0.25 * farWithout + 1e-4);
}

} // namespace
