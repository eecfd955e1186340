// The stability suite's cases (renderer/stability/cases.h) at a small size (80x60, lavapipe, the
// quick timeline: 37 frames of warm-up, hold and reference; 2 CPU cores). The suite's targets
// (docs/stability.md) are held for every case under both cache rules (EveryCase); the other
// tests hold what a case measures beyond them (stale light, the history a cut keeps), within
// bounds set from the value measured when each was written.
#include "stability/run.h"
#include "support.h"

#include <cmath>
#include <map>
#include <ostream>
#include <tuple>

using namespace ssgi;
using namespace ssgi::stability;

namespace {

RunOptions quick() {
    RunOptions o;
    o.width = 80, o.height = 60;
    o.warmup = o.hold = o.converge = 37; // one frame past the 36 rotations that converge a pixel
    return o;
}

// Each case runs once per process, cache rule (cache_method 0, the thesis's, or 1, the
// running mean) and bounce (`indirect_method`; kDefaultBounce: the default, the world cache);
// the tests read its figures.
constexpr int kDefaultBounce = -1;
const CaseResult& result(const std::string& name, int method = 0, int bounce = kDefaultBounce) {
    static std::map<std::tuple<std::string, int, int>, CaseResult> results;
    auto it = results.find({name, method, bounce});
    if (it == results.end()) {
        RunOptions o = quick();
        if (method != 0) o.settings.emplace_back("cache_method", method);
        if (bounce != kDefaultBounce) o.settings.emplace_back("indirect_method", bounce);
        it = results
                 .emplace(std::tuple{name, method, bounce},
                          runCase(test::context(), findCase(name), o))
                 .first;
        const CaseResult& r = it->second;
        const std::string bounceName =
            bounce == kDefaultBounce ? "default" : std::to_string(bounce);
        std::printf("%s (cache_method %d, indirect_method %s): region %zu px, NaN/Inf %zu, "
                    "still flicker %.2g, "
                    "recovery %d, settled %.3g / elsewhere %.3g (a fresh start %.3g), over fresh "
                    "%.3gx, AO kept %.3f, stale %.3g\n",
                    name.c_str(), method, bounceName.c_str(), r.regionPixels, r.nonFinite,
                    r.stillFlicker, r.recoveryFrames, r.convergedError, r.restError,
                    r.freshSettledError, r.excessOverFresh + 1.0, r.reusedAtChange, r.staleAfter);
    }
    return it->second;
}

using StabilityTest = test::VulkanTest;

// The cases the other tests do not run, short and tiny, with pixels converging after 4
// rotations so that skipping, refresh and every reset happen within a few frames.
TEST_F(StabilityTest, NoNaNOrInfInAnyImageOfAnyCase) {
    RunOptions o = quick();
    o.width = 48, o.height = 36;
    o.warmup = o.hold = o.converge = 6;
    o.stillFrames = 2;
    o.settings = {{"cache_rotations", 4}};
    for (const Case& c : suite()) {
        if (c.name == "pillar" || c.name == "moving-light" || c.name == "cut") continue;
        const CaseResult r = runCase(test::context(), c, o);
        EXPECT_EQ(r.nonFinite, 0u)
            << c.name << ": NaN/Inf in " << r.nonFiniteImages.size() << " image(s), e.g. "
            << (r.nonFiniteImages.empty() ? "" : *r.nonFiniteImages.begin());
    }
}

// The Cornell box, the spot light sliding along the ceiling for 8 frames, then still.
TEST_F(StabilityTest, AMovedLightLeavesNoStaleLightingAfterOneFrame) {
    const CaseResult& r = result("moving-light");
    EXPECT_EQ(r.nonFinite, 0u);
    EXPECT_GT(r.regionPixels, 1000u); // measured 2063 of 4800
    // Measured: at most 0.0032 of the old-to-new change remains from the frame after the light
    // stopped on (setLight restarts the shadow and the bounce light; 0.0006 while the converged
    // reference shared the fresh start's samples).
    EXPECT_LT(std::abs(r.staleAfter), 0.02);
    // The region settles near the pixels the light did not change (measured 0.84x here, 1.7x
    // at 96x72; so the frames until it stays within twice theirs vary with the size: 1 here,
    // 33 at 96x72, 1 at 160x120).
    EXPECT_LT(r.convergedError, 2.5 * r.restError);
    // Measured: the region's error is 0.78x a fresh renderer's (the AO, which the light does
    // not touch, keeps its converged history).
    EXPECT_LT(r.excessOverFresh, 0.2);
    EXPECT_LE(r.stillFlicker, 1e-4); // measured 0 (2.6e-4 to 3.6e-4 while the refresh blended)
}

// The Cornell box, the short block sliding 11 cm along its object path for 8 frames, then
// still: the thesis assumes static objects; the renderer restarts, per pixel, the AO near the
// block's old and new place and the shadow on paths to the light passing near them, and the
// bounce light whole.
TEST_F(StabilityTest, AMovedObjectLeavesNoStaleLightingAfterOneFrame) {
    const CaseResult& r = result("moving-object");
    EXPECT_EQ(r.nonFinite, 0u);
    EXPECT_GT(r.regionPixels, 300u); // measured 613 of 4800
    // Measured: 0.0051 of the old-to-new change remains from the frame after the block stopped.
    EXPECT_LT(std::abs(r.staleAfter), 0.02);
    // Settled, the region is near where a fresh renderer settles (measured 1.17x, its restarted
    // cells still refreshing; 0.99x at 2048 refreshes a frame. The world cache's error near the
    // block's contacts is 2.8x the rest's in a fresh start too, the interleaved bounce's 0.88x),
    // and over the first frames within a fresh renderer's error (measured 1.08x and 0.72x: the
    // restarted pixels accumulate like a fresh start's; the rest keep their converged history).
    EXPECT_LT(r.convergedError, 1.5 * r.freshSettledError);
    EXPECT_LT(r.excessOverFresh, 1.0);
    EXPECT_LE(r.stillFlicker, 1e-4); // measured 0 (2.1e-4 while the refresh blended)
}

// Sponza, a cut from the west end of the atrium to the east end looking back (its path key is
// marked "cut", and the 180-degree turn is beyond cache_cut_angle_deg as well): no history
// survives it, and every pixel fares as a fresh renderer's does. Before cuts existed,
// reprojection kept the AO history of 0.30 of the pixels, at 15x a fresh start's error there.
TEST_F(StabilityTest, ACameraCutRestartsEveryHistory) {
    const CaseResult& r = result("cut");
    EXPECT_EQ(r.nonFinite, 0u);
    EXPECT_LT(r.reusedAtChange, 1e-3); // measured 0
    EXPECT_LT(r.keptUnseen, 1e-3);
    // The first 8 frames after the cut against a fresh renderer's: measured 1.24x (each frame's
    // pattern turn and scale differ between the two).
    double tested = 0.0, fresh = 0.0;
    for (const FrameRecord& f : r.frames)
        if (f.sinceChange >= 0 && f.sinceChange < 8) tested += f.errorRest, fresh += f.freshRest;
    std::printf("cut: error over a fresh start's in the first 8 frames %.2fx\n", tested / fresh);
    EXPECT_LT(tested, 1.5 * fresh);
    EXPECT_LE(r.stillFlicker, 1e-4); // measured 1e-5 (2.5e-4 while the refresh blended)
}

// The suite's targets (docs/stability.md), held for every case under both cache rules (0, the
// thesis's; 1, the running mean), against a fresh renderer at the final camera that takes the
// same samples in the same frames (a resize's "rest" is the same timeline without the resize):
// - recovered within 8 frames after the last change: from then on the region's error stays
//   within twice that of the pixels the change left alone or of the fresh start's at that age;
// - over the first 8 frames, the region's error at most 1.5x the fresh start's;
// - settled (the last 4 frames) within 2x where the fresh start settles, in the region and
//   elsewhere;
// - no NaN or Inf, and a still camera's flicker at most 1e-4.
// docs/stability.md has what each case measures at 96x72, commit by commit. Before
// the bounce light was computed anew while the camera moves (cache_blur_indirect 4), the running
// mean's halos never recovered, its grazing floor stayed at 2.0x a fresh start's error and the
// thesis rule's pillar at 1.8x. Some 20 s of CPU a case.
struct CaseUnderRule {
    std::string name;
    int method;
    int bounce = kDefaultBounce; // indirect_method
};

void PrintTo(const CaseUnderRule& c, std::ostream* os) {
    *os << c.name << " under cache_method " << c.method << " with indirect_method " << c.bounce;
}

class EveryCase : public StabilityTest, public ::testing::WithParamInterface<CaseUnderRule> {};

TEST_P(EveryCase, RecoversLikeAFreshStart) {
    const CaseUnderRule& p = GetParam();
    const CaseResult& r = result(p.name, p.method, p.bounce);
    EXPECT_EQ(r.nonFinite, 0u);
    EXPECT_LE(r.stillFlicker, 1e-4);
    EXPECT_GE(r.recoveryFrames, 0) << "never recovered";
    EXPECT_LE(r.recoveryFrames, 8);
    // Elsewhere: the pixels outside the region, over the last 4 frames that both renderers drew
    // (a resize has no such pixels; its region is the whole image).
    std::vector<double> rest, freshRest;
    for (const FrameRecord& f : r.frames)
        if (f.sinceChange >= 0 && std::isfinite(f.errorRest) && std::isfinite(f.freshRest))
            rest.push_back(f.errorRest), freshRest.push_back(f.freshRest);
    if (rest.size() >= 4 && r.spec.resizeScale <= 0.0f) {
        double tested = 0.0, fresh = 0.0;
        for (size_t k = rest.size() - 4; k < rest.size(); ++k)
            tested += rest[k], fresh += freshRest[k];
        std::printf("%s (cache_method %d): settled elsewhere %.3g, a fresh start's %.3g\n",
                    p.name.c_str(), p.method, tested / 4, fresh / 4);
        // The scrub pine under the running mean held 2.9x here while a value the shadow's
        // agreeing texels carried through the motion stayed converged after the stop
        // (temporal.comp CARRIED; docs/stability.md).
        EXPECT_LE(tested, 2.0 * fresh) << "settled elsewhere";
    }
    // A resize's first 8 frames over the renderer's that never resized: printed, not held. On a
    // still camera (resize-still) a resize still restarts the shadow's history, whose budget
    // is 0 (docs/stability.md: 2.4x under the thesis's rule, 7.4x under the running mean).
    if (std::isfinite(r.excessOverUnresized))
        std::printf("%s (cache_method %d): first 8 frames over the unresized renderer's %.3gx\n",
                    p.name.c_str(), p.method, r.excessOverUnresized + 1.0);
    if (r.regionPixels == 0) return; // a cut keeps no history: nothing to compare in a region
    EXPECT_LE(r.excessOverFresh + 1.0, 1.5) << "first 8 frames over a fresh start's";
    EXPECT_LE(r.convergedError, 2.0 * r.freshSettledError) << "settled in the region";
}

std::vector<CaseUnderRule> everyCaseUnderBothRules() {
    std::vector<CaseUnderRule> all;
    for (int method : {0, 1})
        for (const Case& c : suite())
            all.push_back({c.name, method});
    return all;
}

std::string caseTestName(const ::testing::TestParamInfo<CaseUnderRule>& info) {
    std::string name = info.param.name + "_cache_method_" + std::to_string(info.param.method);
    for (char& ch : name)
        if (ch == '-') ch = '_';
    return name;
}

INSTANTIATE_TEST_SUITE_P(Suite, EveryCase, ::testing::ValuesIn(everyCaseUnderBothRules()),
                         caseTestName);

// The suite above runs the default bounce, the world cache (indirect_method 3). The interleaved
// bounce (indirect_method 1) keeps a screen-space history instead, which the light, an object
// and the depth edges test: the same targets.
INSTANTIATE_TEST_SUITE_P(
    InterleavedBounce, EveryCase,
    ::testing::Values(CaseUnderRule{"moving-light", 0, 1}, CaseUnderRule{"moving-light", 1, 1},
                      CaseUnderRule{"moving-object", 0, 1}, CaseUnderRule{"moving-object", 1, 1},
                      CaseUnderRule{"halos", 0, 1}, CaseUnderRule{"halos", 1, 1}),
    caseTestName);

} // namespace
