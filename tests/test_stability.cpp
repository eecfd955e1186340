// The stability suite's cases (renderer/stability/cases.h) at a small size, each measure held
// within a bound set from the value measured when it was written (80x60, lavapipe, the thesis
// rule unless a test says otherwise, the quick timeline: 37 frames of warm-up, hold and
// reference; 2 CPU cores). Where issue 20 sets a target (still flicker at most 1e-4, the first 8
// frames after a change within 1.5x a fresh start's error), the test holds the target. The
// whole file takes about 130 s of CPU.
#include "stability/run.h"
#include "support.h"

#include <map>

using namespace ssgi;
using namespace ssgi::stability;

namespace {

RunOptions quick() {
    RunOptions o;
    o.width = 80, o.height = 60;
    o.warmup = o.hold = o.converge = 37; // one frame past the 36 rotations that converge a pixel
    return o;
}

// Each case runs once per process and cache rule (cache_method 0, the thesis's, or 1, the
// running mean); the tests read its figures.
const CaseResult& result(const std::string& name, int method = 0) {
    static std::map<std::pair<std::string, int>, CaseResult> results;
    auto it = results.find({name, method});
    if (it == results.end()) {
        RunOptions o = quick();
        if (method != 0) o.settings = {{"cache_method", method}};
        it = results.emplace(std::pair{name, method}, runCase(test::context(), findCase(name), o))
                 .first;
        const CaseResult& r = it->second;
        std::printf("%s (cache_method %d): region %zu px, NaN/Inf %zu, still flicker %.2g, "
                    "recovery %d, settled %.3g / elsewhere %.3g (a fresh start %.3g), over fresh "
                    "%.3gx, AO kept %.3f, stale %.3g\n",
                    name.c_str(), method, r.regionPixels, r.nonFinite, r.stillFlicker,
                    r.recoveryFrames, r.convergedError, r.restError, r.freshSettledError,
                    r.excessOverFresh + 1.0, r.reusedAtChange, r.staleAfter);
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

// Sponza, the camera sliding past a pillar: the wall it reveals has no history.
TEST_F(StabilityTest, ADisocclusionRecoversWithinEightFrames) {
    const CaseResult& r = result("pillar");
    EXPECT_EQ(r.nonFinite, 0u);
    EXPECT_GT(r.regionPixels, 200u) << "the pan must reveal something"; // measured 470
    // Frames after the camera stopped until the revealed wall's error stays within twice that
    // of the pixels that kept their history or of a fresh start at the same age (12 before the
    // history was filtered over same-surface texels only: the bilinear fetch carried the
    // pillar's lit edge into the revealed wall, and the thesis's rule barely lets a small
    // difference through). Issue 20's targets: recovered within 8 frames, at most 1.5x a fresh
    // start's error over the first 8 frames (measured 0.40x), and settled within 2x where a
    // fresh start settles (measured 0.91x; 1.27x while the converged reference shared the fresh
    // start's samples; `stability --quick`'s pillar went from 3.2x to 0.3x when histories that
    // motion blurred began to accumulate again once the camera stopped).
    EXPECT_GE(r.recoveryFrames, 0);
    EXPECT_LE(r.recoveryFrames, 8);
    EXPECT_LT(r.excessOverFresh, 0.5);
    EXPECT_LT(r.convergedError, 2.0 * r.freshSettledError);
    // Issue 20's target for a still camera: at most 1e-4 (measured 0: a converged history that
    // no motion blurred is kept as it is by the refresh tile; 0.9e-4 to 1.4e-4 while the tile
    // blended its fresh samples in).
    EXPECT_LE(r.stillFlicker, 1e-4);
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
    // Measured: 0.88x the pixels the move did not change, 0.72x a fresh renderer's
    // error over the first frames (the restarted pixels accumulate like a fresh start's; the
    // rest keep their converged history).
    EXPECT_LT(r.convergedError, 2.5 * r.restError);
    EXPECT_LT(r.excessOverFresh, 1.0);
    EXPECT_LE(r.stillFlicker, 1e-4); // measured 0 (2.1e-4 while the refresh blended)
}

// Sponza, a cut from the west end of the atrium to the east end looking back (its path key is
// marked "cut", and the 180-degree turn is beyond cache_cut_angle_deg as well): no history
// survives it, and every pixel fares as a fresh renderer's does (issue 20). Before cuts existed,
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

// A pillar leaves the screen as the camera slides: the AO history near it held its occlusion,
// which no frame at the final view can compute (cache_screen_edge restarts the pixels whose AO
// radius the screen's edge crossed while the camera moved). Issue 20's target, for both cache
// rules: over the first 8 frames after the camera stopped, the region's error at most 1.5x a
// fresh start's at the final camera (96x72, --quick: 2.49x and 3.11x before the rule, 1.14x
// and 0.66x with it; here 1.22x and 0.62x).
TEST_F(StabilityTest, AnOccluderThatLeftTheScreenLeavesNoGhost) {
    for (int method : {0, 1}) {
        const CaseResult& r = result("screen-edge", method);
        EXPECT_EQ(r.nonFinite, 0u) << "cache_method " << method;
        EXPECT_GT(r.regionPixels, 100u) << "the pillar's receivers must be on screen";
        EXPECT_LE(r.excessOverFresh + 1.0, 1.5) << "cache_method " << method;
        EXPECT_LE(r.stillFlicker, 1e-4) << "cache_method " << method;
    }
}

} // namespace
