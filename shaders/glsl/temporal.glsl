// Reverse reprojection into an effect's history (thesis 3.1.1) and the reuse test (3.1.2),
// shared by the effect passes (to skip converged pixels) and the temporal passes (to blend).
// Needs: frame, historyViewDepth (last frame's G-buffer view depths, shared by every cached
// effect), reprojection (the reprojection pass's image of this frame, reproject.comp),
// historyCount (the effect's rotation counts, 0 where it holds nothing, and whether a pixel is
// due: packCount), screen_space.glsl; loadPixelToWorld() called in main(). The temporal pass,
// which binds every effect's counts, defines SSGI_TEMPORAL_PASS and binds no historyCount.
#ifndef SSGI_TEMPORAL_GLSL
#define SSGI_TEMPORAL_GLSL

#include "reprojection.glsl"

// What an effect stores for a pixel it skips (converged: its cache holds the value), where a
// value computed this frame has alpha 1; the temporal pass and the indirect light's filter tell
// the two apart with wasSkipped.
const vec4 SKIPPED = vec4(0.0);
bool wasSkipped(vec4 value) {
    return value.a < 0.5;
}
// A scalar effect's value of the frame (the shadow, the AO: CachedEffect::scalar) is one half
// float (R16F), never negative where computed; a pixel it skips holds SCALAR_SKIPPED.
const vec4 SCALAR_SKIPPED = vec4(-1.0);
// An effect's value of the frame as value (rgb) and whether it was computed (alpha: 1, or 0 for
// SKIPPED), whichever layout holds it.
vec4 effectValue(sampler2D image, bool scalar, ivec2 pixel) {
    vec4 t = texelFetch(image, pixel, 0);
    return !scalar ? t : t.r < 0.0 ? SKIPPED : vec4(t.rrr, 1.0);
}

// An exact effect (CachedEffect::exact: computed without noise) converges in one rotation.
bool exactEffect(CacheConstants cache) {
    return cache.rotations <= 1;
}

// A cache's count texel (R8_UNORM, EffectCache::countHistory; shared_cache.h countCode): the rotations
// accumulated (0: the pixel holds nothing), and whether the pixel is due. Sampled, the byte reads
// as code / 255, which is 0 only where the pixel holds nothing.
float packCount(float count, bool due) {
    return countCode(count, due) / 255.0;
}
float unpackCount(float stored) {
    return countOfCode(round(stored * 255.0));
}
bool unpackDue(float stored) {
    return dueOfCode(round(stored * 255.0));
}

struct Reprojection {
    bool valid;    // the pixel saw the same surface last frame, and the effect holds it
    vec2 uv;       // where, in last frame's image
    ivec2 texel;   // the history texel that passed the test (the nearest, or one beside it)
    float count;   // rotations accumulated there
    int footprint; // SurfaceReprojection.footprint: which bilinear texels hold the surface
    bool due;      // the temporal pass asked for it to be computed (REUSE_WHILE_MOVING)
};

// Whether an object that moved since the last frame may have changed this pixel's value: the
// pixel lies within reach of a moved box (occlusion within a radius), or its segment to the
// light passes within reach of one (shadows; the reach covers the light's disk and the shadow
// map's filter). Beyond the thesis, which assumes static objects.
bool movedNearby(vec3 world, CacheConstants cache) {
    int mode = cache.motionTest;
    if (mode == MOTION_RESTART_ALL) return false;
    for (int i = 0; i < int(frame.motion.x); ++i) {
        vec3 lo = frame.movedBoxes[2 * i].xyz, hi = frame.movedBoxes[2 * i + 1].xyz;
        if (mode == MOTION_NEAR_BOX) {
            vec3 outside = max(max(lo - world, world - hi), vec3(0.0));
            if (length(outside) <= cache.motionReach) return true;
            continue;
        }
        vec3 light = frame.lightPosition.xyz;
        float texel = distance(light, 0.5 * (lo + hi)) * 2.0 * frame.lightFrustum.z /
                      frame.lightFrustum.w;
        float reach = cache.motionReach + 3.0 * texel;
        lo -= reach;
        hi += reach;
        // Slab test of the segment world -> light against the widened box.
        vec3 d = light - world;
        vec3 inv = 1.0 / (abs(d) + 1e-30) * sign(d + 1e-30);
        vec3 t0 = (lo - world) * inv, t1 = (hi - world) * inv;
        float enter = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
        float leave = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), 1.0));
        if (enter <= leave) return true;
    }
    return false;
}

// Whether the camera moved since the last frame.
bool cameraMoved() {
    return frame.cameraMoved != 0.0;
}

// Beyond the thesis, the screen's edge: an effect that gathers from the screen within a radius
// (the AO: MOTION_NEAR_BOX, motionReach) sees only the part of that radius on screen. Where the
// camera moved the image's edges across the radius around W_t (the part cut off by an edge grew
// or shrank since the history was computed), the history saw another part of the scene than
// this frame can (an occluder that has left the screen, or one that has come on), so it starts
// over, as a still camera at this view has it. The image's edges are the rendered ones, guard
// band included; an edge that moved along itself (a sideways pan, for the top and bottom) cuts
// off the same part and keeps the history.
// Changes below a thirtieth of a pixel are rounding.
const float EDGE_TOLERANCE = 1.0 / 30.0;
bool gatherMeetsEdge(vec3 world, vec4 previousClip, CacheConstants cache) {
    if ((cache.reprojection & REPROJECT_SCREEN_EDGE) == 0 || cache.motionTest != MOTION_NEAR_BOX ||
        cache.motionReach <= 0.0)
        return false;
    if (!cameraMoved()) return false;
    vec4 clip = frame.viewProjection * vec4(world, 1.0);
    vec2 size = frame.viewport.xy;
    float pixelsAtUnitDepth = abs(frame.projection[1][1]) * 0.5 * size.y;
    vec2 now = (clip.xy / clip.w * 0.5 + 0.5) * size;
    vec2 then = (previousClip.xy / previousClip.w * 0.5 + 0.5) * size;
    float reachNow = cache.motionReach * pixelsAtUnitDepth / max(clip.w, tinyLength());
    float reachThen = cache.motionReach * pixelsAtUnitDepth / max(previousClip.w, tinyLength());
    // How far the radius reaches past each edge (left and top, right and bottom), in pixels.
    vec4 cutNow = max(vec4(reachNow - now, now + reachNow - size), 0.0);
    vec4 cutThen = max(vec4(reachThen - then, then + reachThen - size), 0.0);
    return any(greaterThan(abs(cutNow - cutThen), vec4(EDGE_TOLERANCE)));
}

// The surface's reprojection into an effect's history: the reprojection pass's `s` (computed
// once for every effect; a settled frame, which runs neither, computes nothing), with `stored`
// the effect's count texel at s.texel. Valid where a texel holds the surface (reprojection.glsl)
// and a value of the effect (its count is not 0), no moved object may have changed it, and the
// screen's edge cuts off what it cut off before.
Reprojection reprojectInto(SurfaceReprojection s, float stored, vec3 world, CacheConstants cache) {
    Reprojection r = Reprojection(false, vec2(0.0), ivec2(0), 0.0, 0, false);
    if (cache.historyValid == 0 || !s.found || stored == 0.0 || movedNearby(world, cache)) return r;
    if (gatherMeetsEdge(world, frame.previousViewProjection * vec4(world, 1.0), cache)) return r;
    r.valid = true;
    r.uv = s.uv;
    r.texel = s.texel;
    r.count = unpackCount(stored);
    r.footprint = s.footprint;
    r.due = unpackDue(stored);
    return r;
}

#ifndef SSGI_TEMPORAL_PASS
// An effect's pass, which binds its own counts as `historyCount`: its reprojection of `pixel`.
Reprojection reproject(ivec2 pixel, vec3 world, CacheConstants cache) {
    if (cache.historyValid == 0) return Reprojection(false, vec2(0.0), ivec2(0), 0.0, 0, false);
    SurfaceReprojection s = unpackReprojection(texelFetch(reprojection, pixel, 0).x, world);
    float stored = s.found ? texelFetch(historyCount, s.texel, 0).r : 0.0;
    return reprojectInto(s, stored, world, cache);
}
#endif

// The top-left pixel of this frame's refresh tile (cache.refreshTileCorner >= 0).
ivec2 refreshTileCorner(CacheConstants cache) {
    return ivec2(cache.refreshTileCorner % REFRESH_TILE_ROW,
                 cache.refreshTileCorner / REFRESH_TILE_ROW);
}

// An exact effect's count (one rotation, CachedEffect::exact) for a value that resampling has
// blurred: converged while the camera moves, computed again once it holds still.
const float EXACT_BLURRED = 1.5;

// Whether every texel of the bilinear footprint around the reprojected point holds the pixel's
// surface: away from depth edges, where resampling reads the pixel's own surface all round.
bool footprintWhole(Reprojection r) {
    return r.footprint == 15;
}

// Whether a history reused while the camera moves (REUSE_WHILE_MOVING) is reused here: it holds
// one computation or more, the temporal pass did not find its blur at the budget, and
// resampling stays on its surface (footprintWhole).
bool reusedWhileMoving(Reprojection r, CacheConstants cache) {
    return (cache.reprojection & REUSE_WHILE_MOVING) != 0 && cameraMoved() && !exactEffect(cache) &&
           r.count >= 1.0 && !r.due && footprintWhole(r);
}

// A converged pixel reuses its cached value instead of computing the effect again; the refresh
// tile, widened by `margin` pixels on every side, is computed although converged.
bool convergedAround(ivec2 pixel, Reprojection r, CacheConstants cache, int margin) {
    if (!r.valid) return false;
    // An exact effect is reused only where resampling stays on its surface: along a depth edge
    // the history's value comes from fewer texels and moves with the edge, and one computation
    // there costs less than the blur it would leave after a stop.
    if (exactEffect(cache) && !footprintWhole(r)) return false;
    if (r.count < float(cache.rotations) && !reusedWhileMoving(r, cache)) return false;
    // Due: the temporal pass found that resampling would take it past its limit if the camera
    // moves; a still camera adds no blur.
    if (r.due && cameraMoved()) return false;
    if (exactEffect(cache) && r.count >= EXACT_BLURRED && !cameraMoved()) return false;
    if (cache.refreshTileCorner < 0) return true;
    ivec2 corner = refreshTileCorner(cache);
    return any(lessThan(pixel, corner - margin)) ||
           any(greaterThanEqual(pixel, corner + cache.tileSize + margin));
}

#ifndef SSGI_TEMPORAL_PASS
bool convergedAround(ivec2 pixel, vec3 world, CacheConstants cache, int margin) {
    return convergedAround(pixel, reproject(pixel, world, cache), cache, margin);
}

bool converged(ivec2 pixel, vec3 world, CacheConstants cache) {
    return convergedAround(pixel, world, cache, 0);
}
#endif

#endif
