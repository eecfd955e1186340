// Image tests on the Vulkan device: what a reader can state about the frame, checked against
// independent geometry computed on the CPU. Validation and synchronization validation are on.
#include "renderer.h"
#include "scene/camera.h"
#include "support.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

using namespace ssgi;

namespace {

class RenderTest : public test::VulkanTest {};

// The lit patch of a narrow spot is inside its cone, its core is lit, and the mirror-image
// spot on the other side of the floor stays dark.
TEST_F(RenderTest, LightFallsWhereTheSpotPoints) {
    Scene scene = loadScene(test::sourcePath("tests/scenes/spot-on-floor.json"));
    test::Frame f = test::render(scene, 256, 256);
    const SpotLight& light = scene.light;
    const glm::vec3 target(1, 0, 0.5f);
    size_t lit = 0, insideInner = 0, litInsideInner = 0, litOutsideOuter = 0;
    for (size_t i = 0; i < size_t(f.width) * f.height; ++i) {
        if (f.position[4 * i + 3] == 0.0f) continue;
        glm::vec3 p = f.at(f.position, i);
        float angle = std::acos(glm::dot(glm::normalize(p - light.position), light.direction));
        bool isLit = f.luminance(f.direct, i) > 0.0f;
        lit += isLit;
        if (angle < light.innerConeAngle) {
            ++insideInner;
            litInsideInner += isLit;
        }
        // Half a degree of slack for a pixel's footprint at the cone's edge.
        if (angle > light.outerConeAngle + glm::radians(0.5f)) litOutsideOuter += isLit;
    }
    EXPECT_GT(insideInner, 100u) << "the spot's core must cover many pixels";
    EXPECT_EQ(litInsideInner, insideInner);
    EXPECT_EQ(litOutsideOuter, 0u);
    EXPECT_GT(lit, insideInner);

    // The pixel where the target projects is lit; its mirror image across the floor's centre
    // is not.
    glm::mat4 vp = projectionMatrix(scene.camera, 1.0f) * viewMatrix(scene.camera);
    for (float sign : {1.0f, -1.0f}) {
        glm::vec3 uvd;
        ASSERT_TRUE(projectToTexture(vp, sign * target, uvd));
        size_t pixel = size_t(uvd.y * f.height) * f.width + size_t(uvd.x * f.width);
        if (sign > 0)
            EXPECT_GT(f.luminance(f.direct, pixel), 0.1f);
        else
            EXPECT_EQ(f.luminance(f.direct, pixel), 0.0f);
    }
}

// On the Cornell box's floor, the pixels in hard shadow are exactly those from which the
// segment to the light crosses a block, up to the pixels along the shadow's edge.
TEST_F(RenderTest, ShadowOfTheBlocksLiesWhereTheLightsGeometryPutsIt) {
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    scene.settings.shadow_taps = 1; // the hard shadow test
    test::Frame f = test::render(scene, 192, 192);
    size_t floor = 0, agree = 0, expectedShadow = 0, renderedShadow = 0;
    for (size_t i = 0; i < size_t(f.width) * f.height; ++i) {
        glm::vec3 p = f.at(f.position, i), n = f.at(f.normal, i);
        if (f.position[4 * i + 3] == 0.0f || std::abs(p.y) > 1e-3f || n.y < 0.99f) continue;
        ++floor;
        bool blocked = test::segmentBlocked(scene, p + 1e-4f * n, scene.light.position);
        bool dark = f.luminance(f.direct, i) == 0.0f;
        expectedShadow += blocked;
        renderedShadow += dark;
        agree += blocked == dark;
    }
    ASSERT_GT(floor, 3000u);
    EXPECT_GT(expectedShadow, floor / 20) << "the blocks must cast a sizeable shadow";
    // Measured at 192x192: 0.9905 (1,255 pixels expected in shadow, 1,230 rendered, of 3,492
    // floor pixels); the disagreement is the one-pixel-wide, shadow-map-aliased shadow edge.
    std::printf("floor pixels %zu, agreement %.4f, shadowed expected %zu rendered %zu\n", floor,
                double(agree) / floor, expectedShadow, renderedShadow);
    EXPECT_GT(double(agree) / floor, 0.985)
        << "expected " << expectedShadow << " rendered " << renderedShadow << " of " << floor;
}

// Each RSM texel is a VPL packed into one RGBA32UI texel (rsm_vpl.glsl), read back decoded: its
// distance along the light's axis is the shadow map's depth made linear (0 exactly where the
// map is empty), and its flux is what the floor reflects of the spot's intensity through the
// texel's solid angle, albedo x I x falloff x (texel side)^2 cos^3 of the angle off the axis.
TEST_F(RenderTest, RsmTexelsHoldTheShadowMapsDepthAndTheFloorsFlux) {
    const Scene scene = loadScene(test::sourcePath("tests/scenes/spot-on-floor.json"));
    Renderer renderer(test::context(), scene, {64, 64, "final", {"rsm.vpls", "rsm.depth"}});
    renderer.renderFrame(scene.camera);
    const std::vector<float> vpls = renderer.readImage("rsm.vpls");
    const std::vector<float> depth = renderer.readImage("rsm.depth");
    ASSERT_EQ(vpls.size(), depth.size());
    const size_t side = size_t(std::lround(std::sqrt(double(vpls.size() / 4))));
    ASSERT_EQ(side * side * 4, vpls.size());
    const LightFrustum frustum = lightFrustum(scene.light, scene.bounds);
    const SpotLight& light = scene.light;
    const double texel = 2.0 * frustum.tanHalfFov / double(side);
    size_t drawn = 0, lit = 0, depthOff = 0, fluxOff = 0;
    for (size_t y = 0; y < side; ++y)
        for (size_t x = 0; x < side; ++x) {
            const size_t i = 4 * (y * side + x);
            const float d = depth[i];
            if (d == 1.0f) {
                EXPECT_EQ(vpls[i + 3], 0.0f) << "texel " << x << ", " << y;
                continue;
            }
            ++drawn;
            const float z = linearDepth(d, frustum.znear, frustum.zfar);
            depthOff += std::abs(vpls[i + 3] - z) > 1e-4f * frustum.zfar; // D32's precision
            // The texel's centre on the unit plane, and its angle off the axis.
            const double u = ((double(x) + 0.5) / double(side) * 2.0 - 1.0) * frustum.tanHalfFov;
            const double v = ((double(y) + 0.5) / double(side) * 2.0 - 1.0) * frustum.tanHalfFov;
            const double cosAxis = 1.0 / std::sqrt(1.0 + u * u + v * v);
            const double t =
                std::clamp((cosAxis - std::cos(light.outerConeAngle)) /
                               (std::cos(light.innerConeAngle) - std::cos(light.outerConeAngle)),
                           0.0, 1.0);
            const double expected =
                0.8 * light.intensity * t * t * texel * texel * cosAxis * cosAxis * cosAxis;
            lit += expected > 0.0;
            for (int c = 0; c < 3; ++c)
                fluxOff += std::abs(vpls[i + c] - expected) > 0.01 * expected + 1e-12;
        }
    // The floor fills the map: a narrow spot's frustum sees nothing else.
    EXPECT_EQ(drawn, side * side);
    EXPECT_GT(lit, side * side / 4);
    EXPECT_EQ(depthOff, 0u);
    EXPECT_EQ(fluxOff, 0u);
}

// An empty box, lit and seen along its plane of symmetry, renders mirror-symmetric: exactly so
// for the deterministic terms (direct light and shadow), and up to sampling noise for the whole
// image, compared in 8x8-pixel blocks that average the noise out.
TEST_F(RenderTest, EmptyBoxUnderACentredLightIsMirrorSymmetric) {
    Scene scene = loadScene(test::sourcePath("tests/scenes/empty-box.json"));
    scene.settings.indirect_method = 1; // the bounce the whole image's bound was measured with
    test::Frame f = test::render(scene, 128, 128);
    auto asymmetry = [&](const std::vector<float>& image, uint32_t block) {
        double difference = 0.0, total = 0.0;
        const uint32_t blocks = f.width / block;
        auto mean = [&](uint32_t bx, uint32_t by, bool mirrored) {
            double sum = 0.0;
            for (uint32_t y = by * block; y < (by + 1) * block; ++y)
                for (uint32_t x = bx * block; x < (bx + 1) * block; ++x)
                    sum +=
                        f.luminance(image, size_t(y) * f.width + (mirrored ? f.width - 1 - x : x));
            return sum / (block * block);
        };
        for (uint32_t by = 0; by < blocks; ++by)
            for (uint32_t bx = 0; bx < blocks; ++bx) {
                double a = mean(bx, by, false), b = mean(bx, by, true);
                difference += std::abs(a - b);
                total += a;
            }
        EXPECT_GT(total, 0.0);
        return difference / total;
    };
    const double direct = asymmetry(f.direct, 1), whole = asymmetry(f.hdr, 8);
    std::printf("mirror asymmetry: direct %.5f per pixel, whole image %.5f per 8x8 block\n", direct,
                whole);
    // Measured at 128x128: direct 0.00233 (the PCF pattern turns per pixel, so the penumbra is
    // not mirrored exactly), whole 0.00614.
    EXPECT_LT(direct, 0.005);
    EXPECT_LT(whole, 0.01);
    // And it is lit: the floor under the light is bright.
    EXPECT_GT(f.luminance(f.hdr, size_t(f.height * 0.85) * f.width + f.width / 2), 0.05f);
}

TEST_F(RenderTest, FrameReportsEveryPassInOrderWithTimings) {
    Scene scene = loadScene(test::sourcePath("tests/scenes/empty-box.json"));
    scene.settings.indirect_method = 1; // the screen-space bounce, whose passes are listed below
    {
        // Under a sky, the sky's maps are drawn before the bounce (whose world cache may read
        // them), and the sky visibility passes (cached) run just before the temporal pass that
        // blends every cached effect, the direct light and the composite.
        Scene open = scene;
        open.sky.zenith = glm::vec3(0.5f);
        Renderer skyRenderer(test::context(), open, {32, 32, "final"});
        skyRenderer.renderFrame(open.camera);
        const auto& t = skyRenderer.timings();
        ASSERT_GE(t.size(), 7u);
        auto at = [&t](const std::string& name) {
            return std::find_if(t.begin(), t.end(),
                                [&name](const PassTiming& p) { return p.name == name; }) -
                   t.begin();
        };
        EXPECT_LT(at("sky.maps"), at("indirect"));
        EXPECT_EQ(t[t.size() - 5].name, "sky_visibility.keep");
        EXPECT_EQ(t[t.size() - 4].name, "sky_visibility");
        EXPECT_EQ(t[t.size() - 3].name, "temporal");
        EXPECT_EQ(t[t.size() - 2].name, "direct");
    }
    RenderOptions options{64, 64, "final"};
    options.logRecording = true; // the second frame's barriers are read below
    Renderer renderer(test::context(), scene, options);
    renderer.renderFrame(scene.camera);
    renderer.renderFrame(scene.camera);
    std::vector<std::string> names;
    for (const auto& t : renderer.timings()) {
        names.push_back(t.name);
        EXPECT_GE(t.milliseconds, 0.0);
    }
    EXPECT_EQ(names, (std::vector<std::string>{"gbuffer", "rsm", "shadow_map", "shadow_map_back",
                                               "light_depth_min", "reprojection", "indirect.keep",
                                               "indirect", "indirect.filter_x", "indirect.filter_y",
                                               "shadow.keep", "shadow", "ao.keep", "ao", "temporal",
                                               "direct", "composite"}))
        << "a black sky needs no sky visibility passes";
    // The second frame's barriers: each G-buffer target goes from being sampled by last frame's
    // compute passes back to an attachment (kept from frame to frame with the cache on, as a
    // still camera does not draw it again: its layout is carried, not discarded).
    size_t found = 0;
    for (const auto& b : renderer.frameGraph().lastBarriers())
        if (b.pass == "gbuffer" && b.image == "gbuffer.albedo") {
            ++found;
            EXPECT_EQ(b.oldLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
            EXPECT_EQ(b.newLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
            EXPECT_TRUE(b.srcStages & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        }
    EXPECT_EQ(found, 1u);
}

// The profile counts the compute invocations each pass dispatched (a pipeline statistics query a
// pass): a full-screen pass covers the image in whole workgroups of at most 16 x 16, skipped
// lanes and all; a graphics pass and a pass turned off count none.
TEST_F(RenderTest, EachPassCountsTheInvocationsItDispatched) {
    if (!test::context().pipelineStatistics)
        GTEST_SKIP() << "this device has no pipeline statistics queries";
    const Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    Renderer renderer(test::context(), scene, {20, 12, "final"});
    renderer.renderFrame(scene.camera);
    renderer.renderFrame(scene.camera); // the RSM and the maps are not drawn again
    size_t screenPasses = 0, turnedOff = 0;
    for (const auto& t : renderer.timings()) {
        if (t.name == "composite" || t.name == "direct" || t.name == "temporal") {
            ++screenPasses;
            EXPECT_GE(t.invocations, 20u * 12u) << t.name;
            EXPECT_LE(t.invocations, 32u * 16u) << t.name;
        }
        if (t.name == "gbuffer") EXPECT_EQ(t.invocations, 0u);
        if (!t.ran) {
            ++turnedOff;
            EXPECT_EQ(t.invocations, 0u) << t.name;
        }
    }
    EXPECT_EQ(screenPasses, 3u);
    EXPECT_GT(turnedOff, 0u);
    EXPECT_EQ(renderer.lastFrameProfile().invocations(), [&] {
        uint64_t sum = 0;
        for (const auto& t : renderer.timings())
            sum += t.invocations;
        return sum;
    }());
}

// The default frame's transient images share memory: their block is about half of what they
// need apart (at 1920x1080 on the bunny, 87.0 of 181.7 MiB), the effects' raw outputs among
// those that take turns, and no history is in it.
TEST_F(RenderTest, TransientImagesShareMemory) {
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    scene.settings.indirect_method = 1; // the screen-space bounce: its "indirect" image is shared
    Renderer renderer(test::context(), scene, {64, 64, "final"});
    const graph::FrameGraph& graph = renderer.frameGraph();
    const graph::FrameGraph::SharedMemory shared = graph.sharedMemory();
    VkDeviceSize apart = 0, all = 0;
    for (const auto& [name, bytes, pair] : graph.imageMemory()) {
        all += bytes;
        if (std::find(shared.images.begin(), shared.images.end(), name) != shared.images.end())
            apart += bytes;
    }
    EXPECT_LT(double(shared.bytes), 0.6 * double(apart));
    EXPECT_EQ(graph.heldMemory(), all - apart + shared.bytes);
    for (const char* name : {"shadow", "ao", "indirect", "direct", "hdr", "ldr"})
        EXPECT_NE(std::find(shared.images.begin(), shared.images.end(), name), shared.images.end())
            << name;
    for (const auto& [name, bytes, pair] : graph.imageMemory()) {
        if (pair.empty()) continue;
        EXPECT_EQ(std::find(shared.images.begin(), shared.images.end(), name), shared.images.end())
            << name << " is a history";
    }
}

TEST_F(RenderTest, AbsurdSizesAreRejectedWithTheLimitNamed) {
    Scene scene = loadScene(test::sourcePath("tests/scenes/empty-box.json"));
    EXPECT_THROW(Renderer(test::context(), scene, {0, 64, "final"}), InputError);
    try {
        Renderer r(test::context(), scene, {100000, 64, "final"});
        FAIL() << "a 100000-pixel-wide image must be refused";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("largest 2D image"), std::string::npos);
    }
    EXPECT_THROW(Renderer(test::context(), scene, {64, 64, "no-such-view"}), InputError);
}

} // namespace

// Scene units do not matter: the bunny in centimetres, metres and hectometres gives
// the same one-bounce light. With the RSM's flux in 16-bit floats the centimetre scene's bounce
// was exactly 0 and the metre scene's 6% short of the hectometre one's.
TEST_F(RenderTest, TheBounceIsTheSameInAnyUnits) {
    Scene scene = loadScene(test::sourcePath("scenes/bunny.json"));
    scene.settings.indirect_method = 1; // the screen-space bounce: its "indirect" image is read
    std::vector<double> means;
    test::Frame reference;
    for (float k : {1.0f, 0.01f, 100.0f}) {
        const test::Frame f = test::render(test::scaledScene(scene, k), 96, 96);
        double sum = 0.0, difference = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < f.pixels(); ++i) {
            if (!f.geometry(i)) continue;
            const double value = f.luminance(f.indirect, i);
            sum += value;
            if (k != 1.0f)
                difference += std::abs(value - reference.luminance(reference.indirect, i));
            ++n;
        }
        means.push_back(sum / double(n));
        if (k == 1.0f)
            reference = f;
        else
            EXPECT_LT(difference / sum, 0.05) << "scale " << k; // measured 0.023 (cm)
    }
    std::printf("bunny's bounce, mean over geometry: %.6g (m), %.6g (cm), %.6g (hm)\n", means[0],
                means[1], means[2]);
    EXPECT_GT(means[0], 0.0);
    EXPECT_NEAR(means[1], means[0], 0.01 * means[0]);
    EXPECT_NEAR(means[2], means[0], 0.01 * means[0]);
}
