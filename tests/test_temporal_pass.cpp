// The temporal pass blends every cached effect in one dispatch (temporal.comp, one slot an
// effect): each slot must give what a dispatch of that effect alone gives (cache_temporal_slots
// 1), whatever the other slots hold, on a panning camera whose histories are resampled, clamped,
// cut by their blur budgets and fall due.
#include "renderer.h"
#include "support.h"

#include <algorithm>
#include <cstring>
#include <functional>

using namespace ssgi;

namespace {

class TemporalPassTest : public test::VulkanTest {
protected:
    // The Cornell box under a sky: four cached effects (shadow, AO, indirect, sky visibility),
    // the scalar histories beside the colour ones.
    Scene scene = [] {
        Scene s = loadScene(test::sourcePath("scenes/cornell-box.json"));
        s.settings.indirect_method = 1; // the screen-space bounce, one of the cached effects
        s.sky.zenith = glm::vec3(0.5f);
        s.sky.horizon = glm::vec3(0.3f);
        return s;
    }();
    static constexpr uint32_t kSize = 64;

    // About a third of a pixel a frame sideways, then still.
    Camera at(int frame) const {
        Camera c = scene.camera;
        c.position.x += 0.004f * float(std::min(frame, 10));
        return c;
    }
};

const char* const kImages[] = {"shadow.history",
                               "shadow.count",
                               "ao.history",
                               "ao.count",
                               "indirect.history",
                               "indirect.count",
                               "sky_visibility.history",
                               "sky_visibility.count",
                               "hdr"};

// The images of kImages after each frame of the path.
std::vector<std::vector<std::vector<float>>>
imagesAlongPath(Renderer& renderer, const std::function<Camera(int)>& at, int frames) {
    std::vector<std::vector<std::vector<float>>> out;
    for (int f = 0; f < frames; ++f) {
        renderer.renderFrame(at(f));
        std::vector<std::vector<float>> images;
        for (const char* name : kImages)
            images.push_back(renderer.readImage(name));
        out.push_back(std::move(images));
    }
    return out;
}

std::vector<std::string> temporalPasses(const Renderer& renderer) {
    std::vector<std::string> names;
    for (const auto& t : renderer.timings())
        if (t.name == "temporal" || t.name.find(".temporal") != std::string::npos)
            names.push_back(t.name);
    return names;
}

// Bit for bit: the slots run the same code on the same inputs, and nothing one slot does (a
// subgroup's vote, an empty slot's stand-in images) may reach another.
TEST_F(TemporalPassTest, OneDispatchGivesWhatADispatchPerEffectGives) {
    for (int method : {0, 1}) {
        Scene s = scene;
        s.settings.cache_method = method;
        // The running mean with reuse while moving: its clamp, its due flags and their vote.
        s.settings.cache_reuse_moving = method == 1;
        auto path = [this](int f) { return at(f); };
        Scene perEffect = s;
        perEffect.settings.cache_temporal_slots = 1;
        Scene three = s; // a full dispatch and one of three empty slots
        three.settings.cache_temporal_slots = 3;
        Renderer one(test::context(), s, {kSize, kSize, "final"});
        Renderer each(test::context(), perEffect, {kSize, kSize, "final"});
        Renderer grouped(test::context(), three, {kSize, kSize, "final"});
        const auto a = imagesAlongPath(one, path, 14);
        const auto b = imagesAlongPath(each, path, 14);
        const auto c = imagesAlongPath(grouped, path, 14);
        EXPECT_EQ(temporalPasses(one), std::vector<std::string>{"temporal"});
        EXPECT_EQ(temporalPasses(each),
                  (std::vector<std::string>{"indirect.temporal", "shadow.temporal", "ao.temporal",
                                            "sky_visibility.temporal"}));
        EXPECT_EQ(temporalPasses(grouped), (std::vector<std::string>{"indirect+shadow+ao.temporal",
                                                                     "sky_visibility.temporal"}));
        size_t moving = 0;
        for (size_t f = 0; f < a.size(); ++f)
            for (size_t i = 0; i < std::size(kImages); ++i) {
                ASSERT_EQ(a[f][i].size(), b[f][i].size());
                EXPECT_EQ(std::memcmp(a[f][i].data(), b[f][i].data(), a[f][i].size() * 4), 0)
                    << kImages[i] << " frame " << f << " method " << method << ": per effect";
                EXPECT_EQ(std::memcmp(a[f][i].data(), c[f][i].data(), a[f][i].size() * 4), 0)
                    << kImages[i] << " frame " << f << " method " << method << ": 3 slots";
                // The path resamples: the histories carry blur while the camera moves.
                if (f > 0 && f <= 10 && std::string(kImages[i]) == "ao.history")
                    for (size_t p = 3; p < a[f][i].size(); p += 4)
                        moving += a[f][i][p] > 0.0f;
            }
        EXPECT_GT(moving, 0u) << "no history carried blur: the camera did not move";
    }
}

} // namespace
