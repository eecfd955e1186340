// SSDO's own fixes (SSDO paper sections 4-5) measured against the path-traced reference: depth
// peeling on a thin occluder and in the bounce's visibility test, contact shadows where an
// object touches its floor.
#include "reference/cache.h"
#include "renderer.h"
#include "support.h"

#include <cmath>
#include <memory>

using namespace ssgi;

namespace {

class SsdoFixesTest : public test::VulkanTest {};

// The reference image of `scene`'s camera in `mode` at w x h, `spp` samples a pixel (cached).
std::vector<float> referenceImage(const Scene& scene, reference::Mode mode, uint32_t w, uint32_t h,
                                  uint32_t spp) {
    reference::ReferenceOptions options;
    options.mode = mode;
    options.width = w;
    options.height = h;
    options.spp = spp;
    return reference::cachedReference(scene, options).rgba;
}

// A renderer of `scene` with depth peeling on or off after 40 frames of its still camera.
std::unique_ptr<Renderer> converged(Scene& scene, uint32_t w, uint32_t h, int peeling) {
    scene.settings.depth_peeling = peeling;
    auto renderer =
        std::make_unique<Renderer>(test::context(), scene, RenderOptions{w, h, "final"});
    for (int frame = 0; frame < 40; ++frame)
        renderer->renderFrame(scene.camera);
    return renderer;
}

// Under a uniform sky of radiance 1 and no other light, converged SSDO is albedo x the open
// fraction of the hemisphere within r_max; the reference's AO is that fraction within the same
// radius. The floor far behind a thin pillar is where one depth layer goes wrong.
TEST_F(SsdoFixesTest, DepthPeelingRemovesTheHaloBehindAThinPillar) {
    Scene scene = loadScene(test::sourcePath("tests/scenes/thin-pillar.json"));
    const uint32_t w = 160, h = 120;
    const std::vector<float> truth = referenceImage(scene, reference::Mode::Ao, w, h, 256);
    auto floorError = [&](int peeling) {
        const auto renderer = converged(scene, w, h, peeling);
        const std::vector<float> ssdo = renderer->readImage("ssdo.history");
        const std::vector<float> position = renderer->readImage("gbuffer.position");
        double sum = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < size_t(w) * h; ++i) {
            // The floor more than a metre behind the pillar: in 3D nothing there is near it.
            if (position[4 * i + 3] == 0.0f || position[4 * i + 1] > 1e-3f ||
                position[4 * i + 2] > 0.2f)
                continue;
            sum += std::abs(ssdo[4 * i] / 0.8f - truth[4 * i]);
            ++n;
        }
        EXPECT_GT(n, 2000u);
        return sum / double(n);
    };
    const double single = floorError(0), peeled = floorError(1);
    std::printf("floor behind the pillar, SSDO sky visibility mean abs error: one layer %.4f, "
                "two layers %.4f\n",
                single, peeled);
    // Measured at 160x120: one layer 0.0421, two layers 0.0247 (0.0426 and 0.0252 before 9bb8c35).
    EXPECT_LT(peeled, 0.9 * single);
}

// Where the bunny touches its floor: the world positions within `radius` of a bunny vertex that
// lies within 3 mm of the floor (its feet and tail), from the scene's own geometry.
std::vector<glm::vec3> contactPoints(const Scene& scene, float floorY) {
    std::vector<glm::vec3> points;
    for (const Instance& instance : scene.instances)
        for (const Vertex& v : scene.meshes[instance.mesh].vertices) {
            const glm::vec3 p = glm::vec3(instance.transform * glm::vec4(v.position, 1.0f));
            if (p.y > floorY + 1e-4f && p.y < floorY + 0.003f) points.push_back(p);
        }
    return points;
}

bool nearAny(const std::vector<glm::vec3>& points, glm::vec3 p, float radius) {
    for (const glm::vec3& q : points)
        if (glm::distance(p, q) < radius) return true;
    return false;
}

// Contact shadows only ever add shadow, only next to geometry, and where the bunny meets its
// floor under a low light (a coarse shadow map whose 4-texel normal offset lets light leak onto
// the paws and the floor beside them) they bring the direct light closer to the disk light's
// path-traced reference, with the second depth layer and without.
TEST_F(SsdoFixesTest, ContactShadowsLowerTheErrorWhereTheBunnyTouchesTheFloor) {
    Scene scene = loadScene(test::sourcePath("tests/scenes/bunny-low-light.json"));
    const uint32_t w = 320, h = 240;
    const float floorY = 0.033f;
    reference::ReferenceOptions options;
    options.mode = reference::Mode::Direct;
    options.width = w;
    options.height = h;
    options.spp = 256;
    const std::vector<float> truth = reference::cachedReference(scene, options).rgba;
    const std::vector<glm::vec3> feet = contactPoints(scene, floorY);
    ASSERT_GT(feet.size(), 10u);

    test::Frame without = test::render(scene, w, h, 40);
    scene.settings.contact_shadows = true;
    scene.settings.depth_peeling = true;
    test::Frame with = test::render(scene, w, h, 40);
    scene.settings.depth_peeling = false;
    test::Frame oneLayer = test::render(scene, w, h, 40);
    size_t darkened = 0, openFloorChanged = 0, near = 0;
    double errorWithout = 0.0, errorWith = 0.0, errorOneLayer = 0.0;
    auto relSquared = [&](const std::vector<float>& image, size_t i) {
        double sum = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double a = image[4 * i + c], b = truth[4 * i + c];
            sum += (a - b) * (a - b) / (b * b + 0.01);
        }
        return sum / 3.0;
    };
    for (size_t i = 0; i < with.pixels(); ++i) {
        if (!with.geometry(i)) continue;
        const float a = with.direct[4 * i], b = without.direct[4 * i];
        ASSERT_LE(a, b + 1e-6f) << "contact shadows never add light";
        darkened += a < b;
        const glm::vec3 p = with.at(with.position, i);
        // The floor more than 12 cm from the bunny's centre has nothing near it to touch.
        if (std::abs(p.y - floorY) < 1e-4f && glm::length(glm::vec2(p.x + 0.017f, p.z)) > 0.12f)
            openFloorChanged += a != b;
        if (nearAny(feet, p, 0.01f)) {
            ++near;
            errorWithout += relSquared(without.direct, i);
            errorWith += relSquared(with.direct, i);
            errorOneLayer += relSquared(oneLayer.direct, i);
        }
    }
    errorWithout /= double(near);
    errorWith /= double(near);
    errorOneLayer /= double(near);
    std::printf(
        "contact shadows darkened %zu pixels; open floor changed %zu; direct light "
        "within 1 cm of the contact (%zu pixels), relMSE: without %.4f, with %.4f (one layer "
        "%.4f)\n",
        darkened, openFloorChanged, near, errorWithout, errorWith, errorOneLayer);
    EXPECT_GT(darkened, 10u);
    EXPECT_EQ(openFloorChanged, 0u);
    EXPECT_GT(near, 200u);
    // Measured at 320x240 (40 frames, 256-spp reference): without 0.0588, with 0.0463 (two
    // layers), 0.0470 (one layer).
    EXPECT_LT(errorWith, 0.95 * errorWithout);
    EXPECT_LT(errorOneLayer, 0.95 * errorWithout);
}

// The Cornell box's ceiling and upper back wall are lit by the bounce alone, from VPLs the tall
// block hides from the camera's view of them in part: one depth layer's thickness guess takes
// the open space behind the block for the block. With the second layer the test knows where the
// block ends; with the light's check (indirect_visibility_light, the default) the light, which
// sees the blocks' tops, tells it the steps above them are open. The ratio of the converged
// bounce to the reference's one bounce, summed over the image's top third.
TEST_F(SsdoFixesTest, DepthPeelingGivesTheCornellBoxsCeilingItsBounce) {
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    scene.settings.indirect_method = 1; // the screen-space bounce, whose visibility test peels
    const uint32_t w = 128, h = 128;
    const std::vector<float> truth = referenceImage(scene, reference::Mode::Indirect, w, h, 1024);
    auto topRatio = [&](int peeling, bool lightCheck) {
        scene.settings.indirect_visibility_light = lightCheck;
        const auto renderer = converged(scene, w, h, peeling);
        const std::vector<float> bounce = renderer->readImage("indirect.history"); // E / pi
        const std::vector<float> albedo = renderer->readImage("gbuffer.albedo");
        const std::vector<float> position = renderer->readImage("gbuffer.position");
        double realtime = 0.0, reference = 0.0;
        for (size_t i = 0; i < size_t(w) * (h / 3); ++i) {
            if (position[4 * i + 3] == 0.0f) continue;
            for (size_t c = 0; c < 3; ++c) {
                realtime += bounce[4 * i + c] * albedo[4 * i + c];
                reference += truth[4 * i + c];
            }
        }
        return realtime / reference;
    };
    const double single = topRatio(0, false), peeled = topRatio(1, false);
    const double checked = topRatio(0, true);
    std::printf("the Cornell box's top third, bounce / reference: one layer %.3f, two layers "
                "%.3f, one layer with the light's check %.3f\n",
                single, peeled, checked);
    // Measured at 128x128 before the light's check: one layer 0.850, two layers 0.981 (at
    // 192x192 0.881 and 1.039; at 96x96 the one layer's guess finds few false occluders, 0.947
    // against 0.932). With the filter's symmetric window: 0.817, 0.942, and 1.025 checked.
    EXPECT_LT(single, 0.92);
    EXPECT_LT(std::abs(peeled - 1.0), 0.5 * std::abs(single - 1.0));
    EXPECT_LT(std::abs(checked - 1.0), 0.5 * std::abs(single - 1.0));
}

} // namespace
