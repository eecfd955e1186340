// The frame's packed images hold every value written into them: a cache's count, a byte with its
// due flag in the top bit (shared_cache.h countCode; cache.h packCount; temporal.glsl), the
// reprojection's point within its texel, texel offset and footprint in one word (shared_cache.h
// REPROJECTION_*; reprojection.glsl), and the HDR output's 21-bit floats (shared.h hdrBits).
#include "cache/cache.h"
#include "renderer.h"
#include "scene/camera.h"
#include "support.h"

#include <cmath>
#include <cstring>

using namespace ssgi;

namespace {

// Every count the temporal pass stores: 0 (holds nothing), half a sample (a resize), 1, an exact
// effect's EXACT_BLURRED (1.5), whole counts up to the rotations (the default 36 and the most,
// CACHE_COUNT_MAX), and the effective number of samples where the blur budget cut the history's
// weight, 1 / ((1 - w)^2 / n + w^2), from a sliver of this frame's weight to nearly all of it.
std::vector<float> countsTheCacheWrites() {
    std::vector<float> counts = {0.0f, 0.5f, 1.5f};
    for (int n = 1; n <= CACHE_COUNT_MAX; ++n)
        counts.push_back(float(n));
    for (float n : {1.0f, 2.0f, 31.0f, 35.0f, 36.0f, float(CACHE_COUNT_MAX)})
        for (float w : {0.0f, 1e-3f, 0.01f, 0.1f, 0.5f, 0.9f, 0.999f, 1.0f})
            counts.push_back(1.0f / ((1.0f - w) * (1.0f - w) / n + w * w));
    return counts;
}

TEST(CacheFormats, ACountAndItsDueFlagRoundTripEveryValueTheCacheWrites) {
    for (float count : countsTheCacheWrites())
        for (bool due : {false, true}) {
            if (due && count < 1.0f) continue; // a due pixel holds one computation or more
            const CountTexel back = unpackCount(packCount({count, due}));
            EXPECT_EQ(back.due, due) << count;
            // Half steps to CACHE_COUNT_HALVES, whole ones above: a step is held exactly (a
            // whole number of samples computed in floats within a thousandth of one too), any
            // other count rounded down, never by a step or more.
            const float step = count <= float(CACHE_COUNT_HALVES) ? 0.5f : 1.0f;
            const float nearest = std::round(count / step) * step;
            if (std::abs(count - nearest) < 1e-3f)
                EXPECT_EQ(back.count, nearest) << count << " due " << due;
            else {
                EXPECT_LE(back.count, count) << due;
                EXPECT_GT(back.count, count - step) << due;
            }
        }
    // Holding nothing is code 0, which no due pixel has; the most rotations fit with the flag.
    EXPECT_EQ(packCount({0.0f, false}), 0);
    const CountTexel none = unpackCount(0);
    EXPECT_EQ(none.count, 0.0f);
    EXPECT_FALSE(none.due);
    EXPECT_EQ(packCount({float(CACHE_COUNT_MAX), true}), 255);
    EXPECT_EQ(unpackCount(255).count, float(CACHE_COUNT_MAX));
}

// A float rounded to nearest, ties to even, at `bits` mantissa bits: within half floats' normal
// range, at 10 bits, the half float an EXR stores.
float roundedMantissa(float v, int bits) {
    uint32_t b = 0;
    std::memcpy(&b, &v, 4);
    const int dropped = 23 - bits;
    const uint32_t lsb = (b >> dropped) & 1u;
    b = ((b + ((1u << (dropped - 1)) - 1u) + lsb) >> dropped) << dropped;
    std::memcpy(&v, &b, 4);
    return v;
}

// The HDR output's 21-bit floats (shared.h hdrBits): every float to within 1/4096, infinities and
// NaNs as they are, and rounded to odd, so that halving the stored value (an EXR of an image
// that fits half floats) gives the float's own nearest half.
TEST(PackedFormats, TheHdrOutputHoldsEveryFloatAndHalvesAsTheFloatDoes) {
    uint32_t state = 12345u;
    auto next = [&state] { return state = state * 1664525u + 1013904223u; };
    for (int i = 0; i < 200000; ++i) {
        // Every exponent from 2^-30 to 2^40 and every mantissa, both signs.
        const float v =
            std::ldexp(1.0f + float(next() >> 9) / float(1u << 23), int(next() % 71) - 30) *
            (next() & 1u ? -1.0f : 1.0f);
        const float back = shader::hdrValue(shader::hdrBits(v));
        ASSERT_LE(std::abs(back - v), std::abs(v) / 4096.0f) << v;
        if (std::abs(v) >= 6.2e-5f && std::abs(v) <= 65504.0f)
            ASSERT_EQ(roundedMantissa(back, 10), roundedMantissa(v, 10)) << v;
    }
    for (float v : {0.0f, -0.0f, 1.0f, 65504.0f, std::ldexp(1.0f, 127), -std::ldexp(1.5f, -100)})
        EXPECT_EQ(shader::hdrValue(shader::hdrBits(v)), v);
    EXPECT_EQ(shader::hdrValue(shader::hdrBits(INFINITY)), INFINITY);
    EXPECT_EQ(shader::hdrValue(shader::hdrBits(-INFINITY)), -INFINITY);
    EXPECT_TRUE(std::isnan(shader::hdrValue(shader::hdrBits(NAN))));
}

class CacheFormatsTest : public test::VulkanTest {
protected:
    static constexpr uint32_t kSize = 64;
    Scene scene = [] {
        Scene s = loadScene(test::sourcePath("scenes/cornell-box.json"));
        s.settings.cache_reuse_moving = 1; // pixels fall due while the camera moves
        return s;
    }();
    Camera turned(float degrees) const {
        Camera c = scene.camera;
        c.orientation = glm::angleAxis(glm::radians(degrees), glm::vec3(0, 1, 0)) * c.orientation;
        return c;
    }
};

// On the device: the counts a panning camera leaves lie within [0, rotations], and a due pixel
// (its sign) holds one computation or more; some fall due, so the sign is exercised.
TEST_F(CacheFormatsTest, TheDevicesCountsStayInRangeAndCarryTheirDueFlag) {
    scene.settings.indirect_method = 1; // the screen-space bounce: its counts are read below
    Renderer r(test::context(), scene, RenderOptions{kSize, kSize});
    for (int f = 0; f < 40; ++f)
        r.renderFrame(turned(0.0f));
    size_t due = 0, held = 0;
    for (int f = 1; f <= 8; ++f) {
        r.renderFrame(turned(0.15f * float(f)));
        for (const std::string effect : {"shadow", "ao", "indirect"}) {
            const std::vector<float> count = r.readImage(effect + ".count");
            for (size_t i = 0; i < count.size(); i += 4) {
                ASSERT_GE(count[i], 0.0f);
                ASSERT_LE(count[i], float(scene.settings.cache_rotations));
                if (count[i + 1] > 0.5f) {
                    ASSERT_GE(count[i], 1.0f) << effect << " pixel " << i / 4;
                    ++due;
                }
                held += count[i] > 0.0f;
            }
        }
    }
    EXPECT_GT(held, 0u);
    EXPECT_GT(due, 0u);
}

// The reprojection's point, offset and footprint, against the same reprojection done on the CPU:
// a still camera's pixels land on their own texel centres exactly (the fixed point holds a centre
// exactly), and a turned camera's within a 4096th of a texel of the float point plus the float
// arithmetic's rounding; the texel that holds the surface is the nearest on these flat walls.
TEST_F(CacheFormatsTest, TheReprojectionHoldsItsPointOffsetAndFootprint) {
    Renderer r(test::context(), scene, RenderOptions{kSize, kSize});
    for (int f = 0; f < 3; ++f)
        r.renderFrame(turned(0.0f));
    std::vector<float> still = r.readImage("reprojection");
    std::vector<float> position = r.readImage("gbuffer.position");
    size_t found = 0, whole = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const float* t = &still[4 * (y * kSize + x)];
            if (position[4 * (y * kSize + x) + 3] == 0.0f) continue;
            ASSERT_EQ(t[2], 4.0f) << x << "," << y; // found, the nearest texel itself
            EXPECT_EQ(t[0], float(x) + 0.5f);
            EXPECT_EQ(t[1], float(y) + 0.5f);
            ++found;
            whole += t[3] == 15.0f;
        }
    EXPECT_GT(found, kSize * kSize / 2);
    EXPECT_GT(whole, found / 2); // most pixels' four bilinear texels hold their surface

    const Camera before = turned(0.0f), after = turned(0.37f);
    r.renderFrame(after);
    const std::vector<float> moved = r.readImage("reprojection");
    position = r.readImage("gbuffer.position");
    const glm::mat4 previous = projectionMatrix(before, 1.0f) * viewMatrix(before);
    size_t compared = 0;
    for (size_t i = 0; i < moved.size(); i += 4) {
        if (position[i + 3] == 0.0f || moved[i + 2] < 0.0f) continue;
        glm::vec3 uvd;
        ASSERT_TRUE(projectToTexture(
            previous, glm::vec3(position[i], position[i + 1], position[i + 2]), uvd));
        const glm::vec2 expected = glm::vec2(uvd) * float(kSize);
        EXPECT_NEAR(moved[i], expected.x, 2e-3f) << i / 4;
        EXPECT_NEAR(moved[i + 1], expected.y, 2e-3f) << i / 4;
        EXPECT_GE(moved[i + 2], 0.0f);
        EXPECT_LE(moved[i + 2], 8.0f);
        EXPECT_LE(moved[i + 3], 15.0f);
        ++compared;
    }
    EXPECT_GT(compared, found / 2);
}

} // namespace
