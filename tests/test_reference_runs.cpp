// How a reference render runs: a staged closed model without black pixels, the same image for
// the same seed whatever the threads, the noise target (early on an honest estimate, never on
// too few samples or no variance), and the cache (the same image back, keys that follow the
// content, a copied entry refused). The estimators' closed-form tests are in test_reference.cpp.
#include "gltf_files.h"
#include "reference/cache.h"
#include "reference_support.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;
using namespace ssgi;
using namespace ssgi::reference;
using ssgi::test::options;
using ssgi::test::testScene;

namespace {

// A closed box as the Khronos sample models draw one (a unit cube of 24 vertices, a normal per
// face), loaded bare: staged on a ground plane and seen from above and to the side. Every pixel
// that shows geometry gets light: along the box's lower edges a pixel-centre ray meets either a
// side face or the ground beside it. A gap between the base and the ground is a slot that such a
// ray can enter, where nothing is lit (4 pixels of 128x128 were exactly black with the ground
// 1e-3 bounding radii below the base).
TEST(Reference, ClosedBoxOnTheGroundHasNoBlackPixel) {
    std::vector<float> positions, normals;
    std::vector<uint32_t> indices;
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-1.0f, 1.0f}) {
            glm::vec3 n(0.0f), u(0.0f), v(0.0f);
            n[axis] = side;
            u[(axis + 1) % 3] = 1.0f;
            v[(axis + 2) % 3] = side; // u x v along n: counter-clockwise seen from outside
            const uint32_t first = uint32_t(positions.size() / 3);
            for (glm::vec2 c :
                 {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
                const glm::vec3 p = 0.5f * (n + c.x * u + c.y * v);
                positions.insert(positions.end(), {p.x, p.y, p.z});
                normals.insert(normals.end(), {n.x, n.y, n.z});
            }
            indices.insert(indices.end(),
                           {first, first + 1, first + 2, first, first + 2, first + 3});
        }
    test::Gltf box;
    box.attribute("POSITION", positions, test::kFloat, "VEC3", 3);
    box.attribute("NORMAL", normals, test::kFloat, "VEC3", 3);
    box.primitive()["indices"] =
        box.accessor(box.view(indices), test::kUnsignedInt, indices.size(), "SCALAR");
    box.doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.8, 0.1, 0.1, 1.0};
    const fs::path file =
        fs::temp_directory_path() / ("ssgi-closed-box-" + std::to_string(getpid()) + ".glb");
    std::ofstream(file, std::ios::binary) << box.glb();
    const Scene scene = loadScene(file.string());
    fs::remove(file);
    // AO at several sizes, so that pixel centres fall along the edges at many offsets: a point
    // on a face or on the ground beside the box sees at least half its hemisphere open, so 32
    // samples all blocked are as good as impossible, where a point in a slot under the base is
    // blocked every time. Then the full image, at enough samples that no lit pixel comes out
    // black by chance.
    size_t black = 0, geometry = 0;
    const auto count = [&](const ReferenceImage& image, const char* mode) {
        for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
            if (image.rgba[4 * i + 3] == 0.0f) continue;
            ++geometry;
            if (image.rgba[4 * i] + image.rgba[4 * i + 1] + image.rgba[4 * i + 2] == 0.0f) {
                ++black;
                ADD_FAILURE() << mode << " " << image.width << "x" << image.height << ": pixel "
                              << i % image.width << ", " << i / image.width << " is black";
            }
        }
    };
    for (uint32_t size = 64; size <= 192; size += 16)
        count(renderReference(scene, scene.camera, options(Mode::Ao, size, 32)), "ao");
    count(renderReference(scene, scene.camera, options(Mode::Full, 128, 64)), "full");
    std::printf("%zu pixels on geometry, %zu black\n", geometry, black);
    EXPECT_GT(geometry, 100000u);
}

TEST(Reference, SameSeedSameImageWhateverTheThreadCount) {
    const Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    ReferenceOptions o = options(Mode::Full, 24, 6);
    o.seed = 7;
    o.jitter = true;
    o.threads = 1;
    const ReferenceImage one = renderReference(scene, scene.camera, o);
    o.threads = 2;
    const ReferenceImage two = renderReference(scene, scene.camera, o);
    o.threads = 5;
    const ReferenceImage five = renderReference(scene, scene.camera, o);
    EXPECT_EQ(one.rgba, two.rgba);
    EXPECT_EQ(one.rgba, five.rgba);
    o.seed = 8;
    const ReferenceImage other = renderReference(scene, scene.camera, o);
    EXPECT_NE(one.rgba, other.rgba) << "a different seed draws different samples";
    EXPECT_EQ(one.samples, 6u);
    EXPECT_EQ(one.nonFiniteSamples, 0u);
}

// A noise target stops the render early, and the estimate it stops on is honest: against a
// converged image, the actual relative error is close to the estimate.
TEST(Reference, NoiseTargetStopsEarlyOnAnHonestEstimate) {
    const Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    ReferenceOptions o = options(Mode::Ao, 32, 4096);
    o.noiseTarget = 0.02;
    const ReferenceImage image = renderReference(scene, scene.camera, o);
    EXPECT_LT(image.samples, 4096u);
    EXPECT_LE(image.noise, 0.02);
    o.noiseTarget = 0.0;
    o.seed = 2; // independent samples
    const ReferenceImage converged = renderReference(scene, scene.camera, o);
    double sum = 0.0;
    for (size_t i = 0; i < size_t(32 * 32); ++i) {
        const double a = image.rgba[4 * i], b = converged.rgba[4 * i]; // grey: one channel
        sum += (a - b) * (a - b) / (b * b + 0.01);
    }
    const double actual = std::sqrt(sum / (32 * 32));
    std::printf("stopped at %u spp, estimated noise %.4f, actual relative error %.4f\n",
                image.samples, image.noise, actual);
    // Measured: stopped at 177 spp, estimate 0.0199, actual 0.0206 (the 4096-spp image's own
    // noise adds a little). Tolerance: within 30% of the estimate.
    EXPECT_NEAR(actual, image.noise, 0.3 * image.noise);
}

// A pixel lit by a rare path: a wall outside a narrow spot light's cone, lit only by the patch of
// floor the spot lights, which about one cosine sample in 80 finds. Its first samples are all 0
// (no variance, estimate 0): the noise target must not stop on that, whether it is reachable
// (a black pixel reported at 0% noise, relMSE 1) or not (1e-6 on the Cornell box).
TEST(Reference, NoiseTargetNeedsSamplesAndAVarianceBeforeItStops) {
    const Scene wall = testScene("ref-narrow-spot-wall.json");
    ReferenceOptions o = options(Mode::Full, 1, 65536);
    o.seed = 2;
    const double truth = renderReference(wall, wall.camera, o).rgba[0];
    for (uint64_t seed = 1; seed <= 4; ++seed) {
        o.seed = seed;
        o.noiseTarget = 0.2;
        const ReferenceImage image = renderReference(wall, wall.camera, o);
        std::printf("seed %llu: %u spp, estimated noise %.3f, value %.4f against %.4f\n",
                    (unsigned long long)seed, image.samples, image.noise, image.rgba[0], truth);
        EXPECT_GE(image.samples, kMinSamplesForNoise);
        EXPECT_GT(image.noise, 0.0);
        EXPECT_LE(image.noise, 0.2);
        // Within 4 estimated standard errors of the 65536-sample value (itself within 4%).
        EXPECT_NEAR(image.rgba[0], truth, 4.0 * image.noise * truth);
    }
    const Scene box = loadScene(test::sourcePath("scenes/cornell-box.json"));
    ReferenceOptions tiny = options(Mode::Full, 1, 512);
    tiny.noiseTarget = 1e-6;
    const ReferenceImage unreachable = renderReference(box, box.camera, tiny);
    EXPECT_EQ(unreachable.samples, 512u) << "a target below the noise runs to the sample cap";
    EXPECT_GT(unreachable.rgba[0], 0.0f);
    // The direct light of a point light draws no random number: its first samples are exact.
    Scene point = box;
    point.light.radius = 0.0f;
    ReferenceOptions direct = options(Mode::Direct, 16, 4096);
    direct.noiseTarget = 0.01;
    const ReferenceImage exact = renderReference(point, point.camera, direct);
    EXPECT_EQ(exact.samples, 2u);
    EXPECT_EQ(exact.noise, 0.0);
}

TEST(Reference, CacheReturnsTheSameImageAndKeysFollowTheContent) {
    const fs::path dir = fs::temp_directory_path() / ("ssgi-ref-cache-" + std::to_string(getpid()));
    fs::remove_all(dir);
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    const ReferenceOptions o = options(Mode::Direct, 16, 4);
    bool hit = true;
    const ReferenceImage first = cachedReference(scene, scene.camera, o, dir.string(), &hit);
    EXPECT_FALSE(hit);
    const ReferenceImage second = cachedReference(scene, scene.camera, o, dir.string(), &hit);
    EXPECT_TRUE(hit);
    EXPECT_EQ(first.rgba, second.rgba);
    EXPECT_EQ(first.samples, second.samples);
    const std::string key = referenceKey(scene, scene.camera, o);
    scene.materials[0].baseColorFactor.r *= 0.5f;
    EXPECT_NE(referenceKey(scene, scene.camera, o), key) << "a material changed";
    scene.materials[0].baseColorFactor.r *= 2.0f;
    EXPECT_EQ(referenceKey(scene, scene.camera, o), key);
    ReferenceOptions more = o;
    more.spp = 8;
    EXPECT_NE(referenceKey(scene, scene.camera, more), key) << "the sample count changed";
    // An entry copied under another request's key (another seed: same size, same sample count)
    // is not that request's image: it is reported and rendered again.
    ReferenceOptions otherSeed = o;
    otherSeed.seed = 2;
    const fs::path otherEntry = dir / (referenceKey(scene, scene.camera, otherSeed) + ".ref");
    fs::copy_file(dir / (key + ".ref"), otherEntry);
    testing::internal::CaptureStderr();
    const ReferenceImage other =
        cachedReference(scene, scene.camera, otherSeed, dir.string(), &hit);
    const std::string said = testing::internal::GetCapturedStderr();
    EXPECT_FALSE(hit);
    EXPECT_NE(other.rgba, first.rgba);
    EXPECT_NE(said.find("is damaged (its checksum does not match its contents and its name)"),
              std::string::npos)
        << said;
    EXPECT_EQ(other.rgba, renderReference(scene, scene.camera, otherSeed).rgba);
    fs::remove_all(dir);
}

} // namespace
