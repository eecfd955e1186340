// A renderer made from another's parts for a change of settings (Renderer's taking constructor):
// it compiles only the pipelines the change specializes otherwise, keeps the images drawn once
// where the change leaves them as they are, and renders the frames a renderer made anew renders,
// bit for bit. (tests/python/test_session.py goes over every setting.)
#include "renderer.h"
#include "scene/camera.h"
#include "support.h"

using namespace ssgi;

namespace {

class RendererPartsTest : public test::VulkanTest {
protected:
    static constexpr uint32_t kWidth = 40, kHeight = 30;
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));

    std::vector<float> fresh(const Scene& s, int frames) {
        Renderer r(test::context(), s, {kWidth, kHeight});
        for (int i = 0; i < frames; ++i)
            r.renderFrame(s.camera);
        return r.readImage("hdr");
    }
};

TEST_F(RendererPartsTest, AChangeOfSettingsIsARendererMadeAnewBitForBit) {
    auto old = std::make_unique<Renderer>(test::context(), scene, RenderOptions{kWidth, kHeight});
    for (int i = 0; i < 3; ++i)
        old->renderFrame(scene.camera);
    const size_t made = old->pipelinesMade();
    // A setting read when recording (a push constant), one a shader is specialized by (the
    // world cache's VPLs), and one that shapes an image drawn once (the voxel grid's size).
    for (const auto& [name, value] :
         std::vector<std::pair<std::string, double>>{{"ao_directions", 5}, // specialized
                                                     {"exposure", 2.0},
                                                     {"world_voxels", 128}}) {
        Scene changed = scene;
        changed.settings = withOverrides(scene.settings, {{name, value}}, "test");
        auto taker = std::make_unique<Renderer>(test::context(), changed,
                                                RenderOptions{kWidth, kHeight}, *old);
        EXPECT_TRUE(old->emptied());
        old.reset();
        for (int i = 0; i < 2; ++i)
            taker->renderFrame(changed.camera);
        EXPECT_EQ(taker->readImage("hdr"), fresh(changed, 2)) << name;
        scene = changed;
        old = std::move(taker);
    }
    // Each change compiled a few pipelines at most; every other pass took the one it had.
    EXPECT_LT(old->pipelinesMade(), made + 12);
    EXPECT_GT(old->pipelinesReused(), 2 * made);
}

// What the old renderer drew for a light other than the new one's (the scene's) is drawn again.
TEST_F(RendererPartsTest, ImagesDrawnForAnotherLightAreDrawnAgain) {
    Renderer old(test::context(), scene, {kWidth, kHeight});
    old.renderFrame(scene.camera);
    SpotLight dimmer = scene.light;
    dimmer.intensity *= 0.25f;
    old.setLight(dimmer);
    old.renderFrame(scene.camera);
    Scene changed = scene;
    changed.settings.exposure = 2.0;
    Renderer taker(test::context(), changed, {kWidth, kHeight}, old);
    taker.renderFrame(changed.camera);
    EXPECT_EQ(taker.readImage("hdr"), fresh(changed, 1));
}

// A sealed light draws no flux into the RSM (renderer.h seal()): a renderer whose camera is
// outside the seal draws it again.
TEST_F(RendererPartsTest, ImagesDrawnForASealedLightAreDrawnAgain) {
    const Scene sealed = loadScene(test::sourcePath("tests/scenes/sealed-light.json"));
    Camera inside = sealed.camera; // in the tall block, with the light, looking down
    inside.position = {0.3685f, 0.3f, 0.35125f};
    inside.orientation = lookRotation({0.0f, -1.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
    inside.yfov = glm::radians(70.0f);
    Renderer old(test::context(), sealed, {kWidth, kHeight});
    old.renderFrame(sealed.camera);
    ASSERT_TRUE(old.seal().has_value());
    Scene changed = sealed;
    changed.settings.exposure = 2.0;
    Renderer taker(test::context(), changed, {kWidth, kHeight}, old);
    taker.renderFrame(inside);
    Renderer anew(test::context(), changed, {kWidth, kHeight});
    anew.renderFrame(inside);
    EXPECT_FALSE(taker.seal().has_value());
    EXPECT_EQ(taker.readImage("hdr"), anew.readImage("hdr"));
}

TEST_F(RendererPartsTest, ABadSizeLeavesThePreviousRendererAsItWas) {
    Renderer old(test::context(), scene, {kWidth, kHeight});
    old.renderFrame(scene.camera);
    Scene changed = scene;
    changed.settings.guard_band = 256;
    EXPECT_THROW(Renderer(test::context(), changed, {1u << 20, kHeight}, old), InputError);
    EXPECT_FALSE(old.emptied());
    old.renderFrame(scene.camera); // still renders
}

} // namespace
