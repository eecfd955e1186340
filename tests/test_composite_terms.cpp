// The lighting terms the composite adds up: handed to it by the passes under their views' names
// (FrameBuild::addCompositeTerm, passes/views.h), each shown by its view by its role.
#include "graph/frame_graph.h"
#include "passes/frame_build.h"
#include "passes/views.h"
#include "renderer.h"
#include "scene_gpu.h"
#include "support.h"

#include <algorithm>
#include <stdexcept>

using namespace ssgi;

namespace {

class CompositeTermsTest : public test::VulkanTest {};

TEST_F(CompositeTermsTest, OnlyATermsViewOnceAndInTheOrderGiven) {
    const Scene scene = loadScene(test::sourcePath("tests/scenes/empty-box.json"));
    SceneGpu sceneGpu(test::context(), scene);
    graph::FrameGraph graph(test::context());
    vk::PipelineStore pipelines(test::context());
    FrameBuild build(test::context(), graph, sceneGpu, pipelines, scene, {16, 16}, 0, {16, 16},
                     glm::dvec3(0.0));
    const graph::ImageRef a =
        graph.createImage("a", VK_FORMAT_R16G16B16A16_SFLOAT, {16, 16}, VK_IMAGE_USAGE_SAMPLED_BIT);
    build.addCompositeTerm("indirect", a);
    build.addCompositeTerm("ao", a);
    EXPECT_THROW(build.addCompositeTerm("shadow", a), std::logic_error); // the composite's own
    EXPECT_THROW(build.addCompositeTerm("bounce", a), std::logic_error); // no such view
    EXPECT_THROW(build.addCompositeTerm("ao", a), std::logic_error);     // twice
    ASSERT_EQ(build.compositeTerms.size(), 2u);
    EXPECT_EQ(build.compositeTerms[0].view, "indirect");
    EXPECT_EQ(build.compositeTerms[0].role, TERM_IRRADIANCE);
    EXPECT_EQ(build.compositeTerms[1].role, TERM_SKY_OCCLUSION);
}

// The hdr image of a view, and one image the same frame made.
std::vector<float> viewOf(const Scene& scene, const std::string& view,
                          const std::string& image = "", std::vector<float>* other = nullptr) {
    Renderer renderer(
        test::context(), scene,
        {32, 32, view,
         image.empty() ? std::vector<std::string>{} : std::vector<std::string>{image}});
    renderer.renderFrame(scene.camera);
    if (other) *other = renderer.readImage(image);
    return renderer.readImage("hdr");
}

TEST_F(CompositeTermsTest, ATermsViewShowsItAndATermTheFrameLacksIsNeutral) {
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    scene.settings.cache = false; // the AO's image is then its term
    std::vector<float> ao;
    const std::vector<float> aoView = viewOf(scene, "ao", "ao", &ao);
    ASSERT_EQ(aoView.size(), ao.size());
    size_t occluded = 0;
    for (size_t i = 0; i < ao.size(); i += 4) {
        // The AO's image holds GTAO's value unclamped (a slice can give more than 1, ao.comp);
        // the view shows it as the composite uses it, clamped at 1.
        const float used = std::min(ao[i], 1.0f);
        ASSERT_EQ(aoView[i], used) << "pixel " << i / 4;
        ASSERT_EQ(aoView[i + 1], used) << "pixel " << i / 4; // one number, shown grey
        occluded += ao[i] < 0.95f;
    }
    EXPECT_GT(occluded, 10u); // along the box's edges and the two boxes

    // With SSDO in its place there is no AO: nothing is occluded by it. Under the box's black
    // sky there is no sky visibility either; without the bounce, no bounce.
    scene.settings.ssdo = true;
    for (float v : viewOf(scene, "ao"))
        ASSERT_EQ(v, 1.0f);
    scene.settings.ssdo = false;
    for (float v : viewOf(scene, "sky-visibility"))
        ASSERT_EQ(v, 1.0f);
    scene.settings.indirect = false;
    const std::vector<float> bounce = viewOf(scene, "indirect");
    for (size_t i = 0; i < bounce.size(); i += 4)
        ASSERT_EQ(bounce[i] + bounce[i + 1] + bounce[i + 2], 0.0f);
}

} // namespace
