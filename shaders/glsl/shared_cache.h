// The temporal cache's declarations shared by C++ and GLSL (included by shared.h): what a moved
// object restarts and what is reused (MOTION_*, REPROJECT_*, REUSE_*), the reprojection pass's
// word (REPROJECTION_*), a cache's count texel (countCode), each effect's CacheConstants, the
// reprojection pass's constants and the temporal pass's slots.
#ifndef SSGI_SHARED_CACHE_H
#define SSGI_SHARED_CACHE_H

#include "shared_language.h"

#ifdef __cplusplus
namespace ssgi::shader {
#endif

// What an object that moved restarts in a cache (CacheConstants.motionTest; EffectCache).
#define MOTION_RESTART_ALL 0 // the whole history: the renderer resets it
#define MOTION_NEAR_BOX 1    // the pixels within motionReach of a moved box (occlusion)
#define MOTION_LIGHT_PATH 2  // the pixels whose path to the light passes within motionReach of one

// What the reprojection does beyond the thesis (CacheConstants.reprojection): where the camera
// moved the screen's edges across the radius the effect gathers within, start over. (The
// reprojection pass's own test, thin geometry included, is ReprojectionConstants'.)
#define REPROJECT_SCREEN_EDGE 2
// What is reused beyond the thesis (CacheConstants.reprojection, with the REPROJECT_ flags):
// while the camera moves, a pixel whose history holds one computation or more is reused until
// its resampling blur reaches the effect's budget (temporal.glsl convergedAround).
#define REUSE_WHILE_MOVING 4
// A view-independent effect's value (CachedEffect::viewIndependent) whose history texels agree
// is resampled without blur: kept while the camera moves (temporal.comp historyAt).
#define REUSE_AGREEING 8

// The reprojection pass's image (R32UI; reprojection.glsl packReprojection): one word holds, in
// its bits 0 to 11 and 12 to 23, where the surface lay in last frame's image within its texel
// along x and y, in REPROJECTION_SUBTEXELs of a texel; in bits 24 to 27 the offset of the texel
// that holds the surface from the one the point lies in, (dx + 1) + 3 (dy + 1) + 1, or 0 where
// none does; in bits 28 to 31 the bilinear footprint. The whole texels follow from the pixel's
// world position (reprojection.glsl unpackReprojection).
#define REPROJECTION_SUBTEXEL 4096
#define REPROJECTION_FRACTION_BITS 12
#define REPROJECTION_OFFSET_SHIFT 24
#define REPROJECTION_FOOTPRINT_SHIFT 28

// A cache's count texel (R8_UNORM, one byte; cache.h kCountFormat): the rotations accumulated
// at a pixel (0: it holds nothing) in its low 7 bits, as half steps up to CACHE_COUNT_HALVES and
// whole ones above, to CACHE_COUNT_MAX (cache_rotations' largest value), and in bit 7 whether
// the temporal pass asked for it to be computed next frame (reuse while moving). A count between
// steps (a blend's effective number of samples where the blur budget cut the history's weight) is
// rounded down, so that a pixel never counts more samples than its blend holds; the counts the
// cache writes as such (0, a resize's half sample, whole counts, an exact effect's 1.5) are steps.
// A due pixel holds one computation or more, so code 0 always means "nothing".
#define CACHE_COUNT_HALVES 32
#define CACHE_COUNT_MAX 95
#define CACHE_COUNT_DUE 128
SSGI_INLINE float countCode(float count, bool due) {
    float c = count < float(CACHE_COUNT_MAX) ? count : float(CACHE_COUNT_MAX);
    // The 1/1000 absorbs float rounding of a blend that is a whole number of samples.
    float steps = c <= float(CACHE_COUNT_HALVES) ? floor(2.0f * c + 1e-3f)
                                                 : float(CACHE_COUNT_HALVES) + floor(c + 1e-3f);
    return steps + (due ? float(CACHE_COUNT_DUE) : 0.0f);
}
SSGI_INLINE float countOfCode(float code) {
    float steps = code >= float(CACHE_COUNT_DUE) ? code - float(CACHE_COUNT_DUE) : code;
    return steps <= float(2 * CACHE_COUNT_HALVES) ? 0.5f * steps
                                                  : steps - float(CACHE_COUNT_HALVES);
}
SSGI_INLINE bool dueOfCode(float code) {
    return code >= float(CACHE_COUNT_DUE);
}

// CacheConstants.refreshTileCorner packs a pixel's x and y into one int (screens are narrower).
#define REFRESH_TILE_ROW 65536

// The temporal cache of one effect (thesis 3.1; docs/temporal-cache.md), as its passes see it
// each frame. Push constants (std430) pack these scalars as C++ does.
struct CacheConstants {
    int historyValid;      // 1 when last frame's history may be read
    int rotations;         // rotations until a pixel is converged
    int refreshTileCorner; // this frame's refresh tile's top-left pixel, x + REFRESH_TILE_ROW * y
                           // (TileRefresh::rect places it), or -1: none
    int tileSize;          // the refresh tile's side, pixels
    float confidenceBias;  // bias of the thesis's confidence rule (eq. 4)
    int runningMean;       // 1 for the running mean, 0 for the thesis's rule
    int motionTest;        // MOTION_*: what a moved object (FrameUniforms.motion) restarts
    float motionReach;     // scene units
    float blurBudget;      // the resampling blur (squared pixels) a cached value may carry:
                           // beyond it the history's weight is cut and the pixel recomputed
    int reprojection;      // REPROJECT_* and REUSE_* flags (temporal.glsl)
};
SSGI_CHECK_SIZE(CacheConstants, 40);

// The reprojection pass's settings (reproject.comp), from the cache's (CacheConstants).
struct ReprojectionConstants {
    float epsilon;    // the reprojection test, in pixel footprints (cache_epsilon)
    int thinGeometry; // 1: where the nearest texel fails, try the texels beside it
    int historyValid; // 0: last frame's view depths hold nothing (every pixel: not found)
};
SSGI_CHECK_SIZE(ReprojectionConstants, 12);

// The temporal pass (temporal.comp) carries up to this many cached effects a dispatch, one a slot;
// its storage buffer (std430, laid out as C++ lays it out) holds each slot's cache this frame.
#define TEMPORAL_EFFECT_SLOTS 4
struct TemporalEffects {
    CacheConstants effects[TEMPORAL_EFFECT_SLOTS];
};
SSGI_CHECK_SIZE(TemporalEffects, 160);

#ifdef __cplusplus
} // namespace ssgi::shader
#endif
#endif
