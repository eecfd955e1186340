// Reverse reprojection of a surface point into last frame's image (thesis 3.1.1, eq. 1-3), by
// geometry alone: which history texel saw the same surface, whatever any effect holds there.
// The reprojection pass (reproject.comp) computes it once a frame for every cached effect;
// temporal.glsl adds what is each effect's own (its counts, moved objects, the screen's edge).
// Needs: frame, historyViewDepth (last frame's G-buffer view depths), screen_space.glsl;
// loadPixelToWorld() called in main().
#ifndef SSGI_REPROJECTION_GLSL
#define SSGI_REPROJECTION_GLSL

#include "pixel_to_world.glsl"

// Last frame's world position at history texel q (xyz; the ray through the texel's centre in
// last frame's view, taken to its view depth), and whether anything was drawn there (w 1, else 0).
vec4 historyPosition(ivec2 q) {
    float depth = texelFetch(historyViewDepth, q, 0).r;
    return vec4(worldAt(historyToWorld, q, depth), depth == 0.0 ? 0.0 : 1.0);
}

struct SurfaceReprojection {
    bool found;    // a history texel holds the surface
    vec2 uv;       // where the point lay in last frame's image
    ivec2 texel;   // the texel that holds it (the nearest, or one beside it)
    int footprint; // bit i: texel floor(uv * size - 0.5) + (i & 1, i >> 1) holds it (bilinear)
};

// C = P_{t-1} V_{t-1} W_t (1), divided by w and mapped to texture space; found where a history
// texel holds a world position within epsilon of W_t (2-3). Epsilon is `epsilonPixels` pixel
// footprints at W_t, so one setting serves every scene scale, widened where the surface is seen
// at a grazing angle, since there neighbouring pixels lie farther apart than one footprint.
// Beyond the thesis, thin geometry (`thinGeometry`): a feature narrower than a pixel (a chair leg,
// a needle) falls between texel centres from one frame to the next, so where the nearest texel
// holds something behind W_t (or nothing), the texels beside it are tried as well, as temporal
// upscalers dilate their reprojection; where it holds something in front of W_t, W_t was hidden
// last frame (a disocclusion) and starts over.
SurfaceReprojection reprojectSurface(vec3 world, vec3 normal, float epsilonPixels,
                                     bool thinGeometry) {
    SurfaceReprojection s = SurfaceReprojection(false, vec2(0.0), ivec2(0), 0);
    vec4 clip = frame.previousViewProjection * vec4(world, 1.0);
    if (clip.w <= 0.0) return s;
    s.uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(s.uv, vec2(0.0))) || any(greaterThanEqual(s.uv, vec2(1.0)))) return s;
    // Positions do not interpolate across edges: the nearest texel's is compared. The history
    // has the frame's size, except in the first frame after a resize (Renderer::continueFrom).
    ivec2 size = textureSize(historyViewDepth, 0);
    s.texel = ivec2(s.uv * vec2(size));
    vec4 h = historyPosition(s.texel);
    float facing = abs(dot(normal, normalize(frame.cameraPosition.xyz - world)));
    float epsilon = epsilonPixels / (pixelsPerUnit(viewDepth(world)) * max(facing, 0.1));
    float nearest = h.w > 0.0 ? distance(h.xyz, world) : 1e30;
    if (nearest > epsilon && thinGeometry &&
        (h.w == 0.0 || (frame.previousViewProjection * vec4(h.xyz, 1.0)).w > clip.w)) {
        ivec2 centre = s.texel;
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                ivec2 q = clamp(centre + ivec2(x, y), ivec2(0), size - 1);
                vec4 m = historyPosition(q);
                float d = m.w > 0.0 ? distance(m.xyz, world) : 1e30;
                if (d < nearest) {
                    nearest = d;
                    s.texel = q;
                }
            }
    }
    s.found = nearest <= epsilon;
    if (!s.found) return s;
    ivec2 base = ivec2(floor(s.uv * vec2(size) - 0.5));
    for (int i = 0; i < 4; ++i) {
        vec4 m = historyPosition(clamp(base + ivec2(i & 1, i >> 1), ivec2(0), size - 1));
        if (m.w > 0.0 && distance(m.xyz, world) <= epsilon) s.footprint |= 1 << i;
    }
    return s;
}

// The reprojection pass's image packs a SurfaceReprojection per pixel in one 32-bit word (R32UI;
// the layout is shared_cache.h's REPROJECTION_*): the point's place within its texel in fixed point,
// within half a 4096th of a texel of the float point (a whole 4096th where that would cross into
// the next texel), so that a still camera's point, a float within rounding of its texel's centre,
// is the centre exactly; the offset of the texel that holds the surface, and the footprint.
// Which texel the point lies in is not stored: whoever unpacks it projects the pixel's world
// position as reprojectSurface did, which lands within float rounding (far below half a texel)
// of the stored point, so the whole texels are those that put the stored fraction nearest to it.
// Nothing found is 0 (its offset code is 1 to 9).
const uint REPROJECTION_FRACTION_MASK = (1u << REPROJECTION_FRACTION_BITS) - 1u;
uint packReprojection(SurfaceReprojection s) {
    if (!s.found) return 0u;
    ivec2 size = textureSize(historyViewDepth, 0);
    ivec2 lies = ivec2(s.uv * vec2(size)); // the texel the point lies in
    ivec2 offset = s.texel - lies + 1;
    vec2 point = s.uv * vec2(size) * float(REPROJECTION_SUBTEXEL);
    uvec2 position = uvec2(round(point));
    // Rounded to the nearest step, unless that takes it into the next texel: the offset counts
    // from the texel the point lies in.
    bvec2 crossed = notEqual(position / uint(REPROJECTION_SUBTEXEL), uvec2(lies));
    position = mix(position, uvec2(floor(point)), crossed);
    uvec2 fraction = position & uvec2(REPROJECTION_FRACTION_MASK);
    return fraction.x | (fraction.y << REPROJECTION_FRACTION_BITS) |
           (uint(offset.x + 3 * offset.y + 1) << REPROJECTION_OFFSET_SHIFT) |
           (uint(s.footprint) << REPROJECTION_FOOTPRINT_SHIFT);
}
// `world`: the pixel's world position (gbufferPosition), from which the texel was found.
SurfaceReprojection unpackReprojection(uint packed, vec3 world) {
    SurfaceReprojection s = SurfaceReprojection(false, vec2(0.0), ivec2(0), 0);
    int offset = int((packed >> REPROJECTION_OFFSET_SHIFT) & 15u) - 1;
    if (offset < 0) return s;
    vec2 size = vec2(textureSize(historyViewDepth, 0));
    vec4 clip = frame.previousViewProjection * vec4(world, 1.0);
    vec2 projected = (clip.xy / clip.w * 0.5 + 0.5) * size;
    vec2 fraction = vec2(packed & REPROJECTION_FRACTION_MASK,
                         (packed >> REPROJECTION_FRACTION_BITS) & REPROJECTION_FRACTION_MASK) /
                    float(REPROJECTION_SUBTEXEL);
    vec2 whole = round(projected - fraction);
    vec2 texels = whole + fraction;
    s.found = true;
    s.uv = texels / size;
    s.footprint = int((packed >> REPROJECTION_FOOTPRINT_SHIFT) & 15u);
    s.texel = ivec2(whole) + ivec2(offset % 3, offset / 3) - 1;
    return s;
}

#endif
