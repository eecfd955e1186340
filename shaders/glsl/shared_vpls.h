// The VPLs' declarations shared by C++ and GLSL (included by shared.h): interleaved sampling's
// subsets and its filter's reach, the polar pattern a pixel draws its VPLs from the reflective
// shadow map with (vplPattern), and the indirect light's and the VPL draw's constants.
#ifndef SSGI_SHARED_VPLS_H
#define SSGI_SHARED_VPLS_H

#include "shared_cache.h"
#include "shared_language.h"

#ifdef __cplusplus
namespace ssgi::shader {
#endif

// How far the interleaved indirect light's filter reaches along each axis, in pixels: its
// radius, and at least across the k x k block of VPL subsets (indirect_reconstruct.comp). The
// refresh tile is widened by as much, so that its pixels find their neighbours computed.
SSGI_INLINE int interleavedFilterReach(int radius, int interleave) {
    return max(radius, interleave / 2);
}

// Interleaved sampling of the VPLs (Keller and Heidrich 2001): the pattern's VPLs 0..n-1 are
// split into k*k disjoint subsets, subset s holding VPLs s, s + k*k, s + 2*k*k, ...; a pixel
// gathers the subset its place in a k x k block names, so every block of k x k pixels gathers
// each VPL exactly once (tests/test_effects.cpp checks it).
SSGI_INLINE int vplSubset(int x, int y, int k) {
    return (y % k) * k + (x % k);
}
// The j-th VPL of subset s, and how many VPLs of n the subset holds.
SSGI_INLINE int vplOfSubset(int s, int j, int k) {
    return s + j * k * k;
}
SSGI_INLINE int vplSubsetSize(int s, int n, int k) {
    return s < n ? (n - s + k * k - 1) / (k * k) : 0;
}

// Where a pixel's VPLs lie in the reflective shadow map: a polar pattern around the pixel's
// projection c, whose density falls as 1/r with the distance r from c (the thesis's r = R xi1,
// 3.3), so that the close VPLs, whose 1/d^2 dominates at creases and contacts, are drawn most.
// - With a sampling radius R > 0 (the RSM paper's r_max): the disk of radius R, density
//   1 / (2 pi R r); points that fall outside the map are lost.
// - With R = 0 (the whole map): the same 1/r density over the map alone, nothing lost. The
//   direction is drawn in proportion to how far the map reaches along it, and r uniformly up to
//   the map's edge: density 1 / (Z r), Z the integral of that reach over the angle. Along an
//   edge at distance d from c the reach is d / cos(psi), whose integral over psi is
//   d asinh(tan psi), so each edge's share of Z and the point where a direction leaves the map
//   are closed forms.
// A sample (xi1, xi2) in [0, 1)^2 maps to r = xi1 x reach, its direction xi2 of the way round;
// of n samples, each stands for the map's area 1 / (n density) = Z r / n (tests/test_effects.cpp
// checks that they add up to the map's area and integrate functions over it).
struct VplPattern {
    vec2 center;
    float radius; // > 0: the disk's; 0: the whole map
    float total;  // Z: 1 / (total r) is the density per unit of the map's uv area
    // The whole-map pattern's edges, counter-clockwise (right, top, left, bottom): each seen
    // from c as the map's right edge turned by e quarter turns, at distance d (at least 1e-4),
    // running from lo to lo + 1 (0 at the foot of the perpendicular from c). `start`:
    // asinh(lo / d), where its directions begin; `before`: the shares of the edges before it.
    vec4 d, lo, start, before;
};

// `center` in [0, 1]^2; an edge closer to it than 1e-4 subtends no angle and gets no share.
SSGI_INLINE VplPattern vplPattern(vec2 center, float radius) {
    VplPattern pattern;
    pattern.center = center;
    pattern.radius = radius;
    pattern.total = 6.28318531f * radius; // the disk's: 2 pi R
    pattern.d = max(vec4(1.0f - center.x, 1.0f - center.y, center.x, center.y), vec4(1e-4f));
    pattern.lo = vec4(-center.y, center.x - 1.0f, center.y - 1.0f, -center.x);
    pattern.start = vec4(0.0f);
    pattern.before = vec4(0.0f);
    if (radius > 0.0f) return pattern;
    float sum = 0.0f;
    for (int e = 0; e < 4; ++e) {
        float d = pattern.d[e];
        pattern.start[e] = asinh(pattern.lo[e] / d);
        pattern.before[e] = sum;
        // The reach along the edge's directions, d / cos(psi), integrates to d asinh(tan psi).
        if (d > 1e-4f) sum += d * (asinh((pattern.lo[e] + 1.0f) / d) - pattern.start[e]);
    }
    pattern.total = sum;
    return pattern;
}

// The point of VPL i of n in the map's uv (outside [0, 1)^2 only for a disk), and its distance
// r from the centre: a Fibonacci lattice, xi1 = (i + stratum) / n (stratum in [0, 1): where in
// its ring) and xi2 = i / golden ratio^2 + rotation / 2 pi (the golden angle's turns).
SSGI_INLINE vec2 vplPatternPoint(VplPattern pattern, int i, int n, float stratum, float rotation,
                                 SSGI_OUT(float) r) {
    float xi1 = (float(i) + stratum) / float(n);
    float turns = float(i) * 0.381966011f + rotation / 6.28318531f;
    float xi2 = turns - floor(turns);
    if (pattern.radius > 0.0f) {
        float theta = 6.28318531f * xi2;
        r = pattern.radius * xi1;
        return pattern.center + r * vec2(cos(theta), sin(theta));
    }
    // The edge whose share holds xi2 (one without a share is passed over), then the offset along
    // it where asinh(offset / d) - start = (the rest of xi2's part) / d.
    float m = xi2 * pattern.total;
    int e = int(m >= pattern.before.y) + int(m >= pattern.before.z) + int(m >= pattern.before.w);
    float d = pattern.d[e];
    float x = exp(pattern.start[e] + (m - pattern.before[e]) / d);
    float offset = clamp(0.5f * d * (x - 1.0f / x), pattern.lo[e], pattern.lo[e] + 1.0f);
    vec2 toExit = vec2(d, offset); // on the right edge; turned by e quarter turns
    if ((e & 1) != 0) toExit = vec2(-toExit.y, toExit.x);
    if ((e & 2) != 0) toExit = -toExit;
    r = xi1 * length(toExit);
    return pattern.center + xi1 * toExit;
}

// The pattern's density per unit of uv area at distance r from the centre (r at least half a
// texel of a map `size` texels wide, where 1/r would spike).
SSGI_INLINE float vplPatternDensity(VplPattern pattern, float r, float size) {
    if (pattern.radius > 0.0f && r > pattern.radius) return 0.0f;
    return 1.0f / (pattern.total * max(r, 0.5f / size));
}

struct IndirectConstants {
    float rotation;     // the pattern's turn this frame (radians)
    float scale;        // its size's jitter (with a sampling radius > 0)
    float radius;       // the sampling radius, a fraction of the RSM (0: the whole map)
    float radialOffset; // common.glsl radialOffset
    int width, height;  // the gather's image (method 0: the half-resolution one)
    int axisX, axisY;   // the interleaved method's filter: the axis of this pass
    CacheConstants cache;
    float visibilityStart; // indirect_visibility_start (indirect_visibility.glsl)
};
SSGI_CHECK_SIZE(IndirectConstants, 76);

// The VPLs of indirect_method 2 (indirect_vpls.comp): the RSM clustered into a coarser VPL
// map, and a pyramid of the VPLs' flux luminance (level 0 the map padded to `paddedSize`, a
// power of two; level `levels` the total) through which VPLs are drawn in proportion to it.
struct VplDrawConstants {
    int cached;     // 1: the draw's points move frame by frame; 0: every frame draws the same
    int mapSize;    // the RSM's side, texels
    int vplMapSize; // the VPL map's side: mapSize / indirect_vpl_cluster, rounded up
    int paddedSize; // the pyramid's level 0 side: a power of two, at least vplMapSize and 8
    int levels;     // log2(paddedSize)
    int unused[3];
};
SSGI_CHECK_SIZE(VplDrawConstants, 32);

#ifdef __cplusplus
} // namespace ssgi::shader
#endif
#endif
