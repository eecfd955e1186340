// Reverse reprojection into an effect's history (thesis 3.1.1) and the reuse test (3.1.2),
// shared by the effect passes (to skip converged pixels) and the temporal passes (to blend).
// Needs: frame, historyViewDepth (last frame's G-buffer view depths, shared by every cached
// effect), historyCount (the effect's rotation counts, 0 where it holds nothing), gbufferNormal,
// screen_space.glsl; loadPixelToWorld() called in main().
#ifndef SSGI_TEMPORAL_GLSL
#define SSGI_TEMPORAL_GLSL

#include "pixel_to_world.glsl"

// What an effect stores for a pixel it skips (converged: its cache holds the value), where a
// value computed this frame has alpha 1; the temporal pass and the indirect light's filter tell
// the two apart with wasSkipped.
const vec4 SKIPPED = vec4(0.0);
bool wasSkipped(vec4 value) {
    return value.a < 0.5;
}

// Last frame's world position (xyz) and the effect's rotation count (w) at texel q: the ray
// through the texel's centre in last frame's view, taken to its view depth (pixel_to_world.glsl).
vec4 historyMeta(ivec2 q) {
    vec3 world = worldAt(historyToWorld, q, texelFetch(historyViewDepth, q, 0).r);
    return vec4(world, texelFetch(historyCount, q, 0).r);
}

// An exact effect (CachedEffect::exact: computed without noise) converges in one rotation.
bool exactEffect(CacheConstants cache) {
    return cache.rotations <= 1;
}

// Whether a history texel (historyMeta) holds the surface at `world`: it holds something, and
// its world position lies within the reprojection test's tolerance.
bool sameSurface(vec4 meta, vec3 world, float epsilon) {
    return !(meta.w == 0.0 || distance(meta.xyz, world) > epsilon);
}

struct Reprojection {
    bool valid;    // the pixel saw the same surface last frame
    vec2 uv;       // where, in last frame's image
    ivec2 texel;   // the history texel that passed the test (the nearest, or one beside it)
    float count;   // rotations accumulated there
    float epsilon; // the world-space tolerance of the test
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
    if (frame.viewProjection == frame.previousViewProjection) return false;
    vec4 clip = frame.viewProjection * vec4(world, 1.0);
    vec2 size = frame.viewport.xy;
    float pixelsAtUnitDepth = abs(frame.projection[1][1]) * 0.5 * size.y;
    vec2 now = (clip.xy / clip.w * 0.5 + 0.5) * size;
    vec2 then = (previousClip.xy / previousClip.w * 0.5 + 0.5) * size;
    float reachNow = cache.motionReach * pixelsAtUnitDepth / max(clip.w, 1e-6);
    float reachThen = cache.motionReach * pixelsAtUnitDepth / max(previousClip.w, 1e-6);
    // How far the radius reaches past each edge (left and top, right and bottom), in pixels.
    vec4 cutNow = max(vec4(reachNow - now, now + reachNow - size), 0.0);
    vec4 cutThen = max(vec4(reachThen - then, then + reachThen - size), 0.0);
    return any(greaterThan(abs(cutNow - cutThen), vec4(EDGE_TOLERANCE)));
}

// C = P_{t-1} V_{t-1} W_t (1), divided by w and mapped to texture space; valid where the
// history holds a world position within epsilon of W_t (2-3). Epsilon is a number of pixel
// footprints at W_t, so one setting serves every scene scale, widened where the surface is seen
// at a grazing angle, since there neighbouring pixels lie farther apart than one footprint.
// Beyond the thesis, thin geometry: a feature narrower than a pixel (a chair leg, a needle) falls
// between texel centres from one frame to the next, so where the nearest texel holds something
// behind W_t (or nothing), the texels beside it are tried as well, as temporal upscalers dilate
// their reprojection; where it holds something in front of W_t, W_t was hidden last frame (a
// disocclusion) and starts over.
Reprojection reproject(vec3 world, vec3 normal, CacheConstants cache) {
    Reprojection r = Reprojection(false, vec2(0.0), ivec2(0), 0.0, 0.0);
    if (cache.historyValid == 0 || movedNearby(world, cache)) return r;
    vec4 clip = frame.previousViewProjection * vec4(world, 1.0);
    if (clip.w <= 0.0) return r;
    r.uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(r.uv, vec2(0.0))) || any(greaterThanEqual(r.uv, vec2(1.0)))) return r;
    // Positions do not interpolate across edges: the nearest texel's is compared. The history
    // has the frame's size, except in the first frame after a resize (Renderer::continueFrom).
    ivec2 size = textureSize(historyCount, 0);
    r.texel = ivec2(r.uv * vec2(size));
    vec4 meta = historyMeta(r.texel);
    float facing = abs(dot(normal, normalize(frame.cameraPosition.xyz - world)));
    float epsilon = cache.epsilon / (pixelsPerUnit(viewDepth(world)) * max(facing, 0.1));
    r.epsilon = epsilon;
    float nearest = meta.w > 0.0 ? distance(meta.xyz, world) : 1e30;
    if (nearest > epsilon && (cache.reprojection & REPROJECT_THIN_GEOMETRY) != 0 &&
        (meta.w == 0.0 || (frame.previousViewProjection * vec4(meta.xyz, 1.0)).w > clip.w)) {
        ivec2 centre = r.texel;
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                ivec2 q = clamp(centre + ivec2(x, y), ivec2(0), size - 1);
                vec4 m = historyMeta(q);
                float d = m.w > 0.0 ? distance(m.xyz, world) : 1e30;
                if (d < nearest) {
                    nearest = d;
                    r.texel = q;
                    meta = m;
                }
            }
    }
    r.valid = nearest <= epsilon && !gatherMeetsEdge(world, clip, cache);
    r.count = r.valid ? meta.w : 0.0;
    return r;
}

// The top-left pixel of this frame's refresh tile (cache.refreshTileCorner >= 0).
ivec2 refreshTileCorner(CacheConstants cache) {
    return ivec2(cache.refreshTileCorner % REFRESH_TILE_ROW,
                 cache.refreshTileCorner / REFRESH_TILE_ROW);
}

// Where a thread's pixel lies. Once the whole screen is settled (camera and light unchanged for
// as many frames as a pixel needs rotations, so every pixel is converged), the effect and
// temporal passes run over the refresh tile alone, offset to it; `divisor` 2 is for the
// half-resolution pass.
ivec2 cachePixel(uvec2 thread, CacheConstants cache, int divisor) {
    if (cache.settled == 0 || cache.refreshTileCorner < 0) return ivec2(thread);
    return ivec2(thread) + refreshTileCorner(cache) / divisor;
}

// The same for a pass whose pixels read their neighbours' values of this frame (the interleaved
// indirect light's filter): its refresh tile widened by `margin` pixels on every side, so that
// the tile's pixels find their neighbours computed. The dispatch is widened to match
// (indirect_interleaved_pass.cpp); the threads offset to the widened tile's corner may fall
// outside the image.
ivec2 cachePixelAround(uvec2 thread, CacheConstants cache, int margin) {
    if (cache.settled == 0 || cache.refreshTileCorner < 0) return ivec2(thread);
    return ivec2(thread) + refreshTileCorner(cache) - margin;
}

// An exact effect's count (one rotation, CachedEffect::exact) for a value that resampling has
// blurred: converged while the camera moves, computed again once it holds still.
const float EXACT_BLURRED = 1.5;

// A converged pixel reuses its cached value instead of computing the effect again; the refresh
// tile, widened by `margin` pixels on every side, is computed although converged.
bool convergedAround(ivec2 pixel, Reprojection r, CacheConstants cache, int margin) {
    if (!r.valid || r.count < float(cache.rotations)) return false;
    if (exactEffect(cache) && r.count >= EXACT_BLURRED &&
        frame.viewProjection == frame.previousViewProjection)
        return false;
    if (cache.refreshTileCorner < 0) return true;
    ivec2 corner = refreshTileCorner(cache);
    return any(lessThan(pixel, corner - margin)) ||
           any(greaterThanEqual(pixel, corner + cache.tileSize + margin));
}

// Whether every texel of the bilinear footprint around the reprojected point holds the pixel's
// surface: away from depth edges, where resampling reads the pixel's own surface all round.
bool footprintWhole(Reprojection r, vec3 world) {
    ivec2 size = textureSize(historyCount, 0);
    ivec2 base = ivec2(floor(r.uv * vec2(size) - 0.5));
    for (int i = 0; i < 4; ++i) {
        vec4 meta = historyMeta(clamp(base + ivec2(i & 1, i >> 1), ivec2(0), size - 1));
        if (!sameSurface(meta, world, r.epsilon)) return false;
    }
    return true;
}

bool convergedAround(ivec2 pixel, vec3 world, vec3 normal, CacheConstants cache, int margin) {
    Reprojection r = reproject(world, normal, cache);
    // An exact effect is reused only where resampling stays on its surface: along a depth edge
    // the history's value comes from fewer texels and moves with the edge, and one computation
    // there costs less than the blur it would leave after a stop.
    if (exactEffect(cache) && r.valid && !footprintWhole(r, world)) return false;
    return convergedAround(pixel, r, cache, margin);
}

bool converged(ivec2 pixel, vec3 world, vec3 normal, CacheConstants cache) {
    return convergedAround(pixel, world, normal, cache, 0);
}

#endif
