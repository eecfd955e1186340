#version 460
#extension GL_GOOGLE_include_directive : require
// The interleaved gather's subsets put back together (Segovia et al. 2006's geometry-aware
// filter), one axis per dispatch (constants.axisX, axisY: the axis). Each pixel averages the
// estimates of the pixels within RADIUS along the axis (at least INTERLEAVE / 2; when the
// window's length is a multiple of INTERLEAVE its two end taps weigh half, so every subset
// weighs the same) that lie on its own surface: within 1.5 pixel footprints of its tangent
// plane per pixel of distance; past INTERLEAVE pixels the window ends where either side leaves
// the surface, so that it stays symmetric about the pixel. A neighbour's estimate belongs to the
// neighbour's normal; it is carried over to the pixel's normal by the ratio f(n_p) / f(n_q) of
// the neighbour's directional sums (indirect_gather.glsl: an L1 spherical harmonic of the light
// its VPLs bring), so that a bumpy surface keeps its shading instead of being blurred flat. The
// directional sums are averaged alike for the next axis. Both axes together give a pixel the
// mean of up to (2 RADIUS)^2 subset estimates, the whole VPL set's many times over; at an edge
// or a contact, those of its own side. A converged pixel is skipped: its cache holds it; the
// refresh tile is computed with a margin as wide as the two axes reach, so that its pixels find
// their neighbours computed.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int INTERLEAVE = 4;
layout(constant_id = 1) const int RADIUS = 8;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 4) uniform usampler2D reprojection;
layout(set = 0, binding = 5) uniform sampler2D historyCount;
layout(set = 0, binding = 6) uniform sampler2D estimates;
layout(set = 0, binding = 7) uniform sampler2D directionals;
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D filtered;
layout(set = 0, binding = 9, rgba16f) uniform writeonly image2D filteredDirectional;
// The effect's history (last frame's blended values; rgb, blur in alpha): what a skipped
// neighbour holds.
layout(set = 0, binding = 10) uniform sampler2D historyValue;
layout(push_constant) uniform IndirectBlock { IndirectConstants constants; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"

// The L1 model's irradiance / pi for normal m (never below a sliver of its mean, so that the
// ratio of two stays finite).
float directionalAt(vec4 sums, vec3 m) {
    return max(0.25 * sums.x + 0.5 * dot(sums.yzw, m), 0.02 * sums.x + 1e-12);
}

// A skipped neighbour's estimate: its history, the whole VPL set's estimate accumulated over
// frames, at the texel the reprojection pass found for it (reused while the camera moves, most
// pixels around a computed one are skipped, and a filter over the computed ones alone would
// average a few subsets, which differ by block: the error shows the blocks). Not found: none.
bool skippedEstimate(ivec2 q, vec3 world, out vec3 estimate) {
    estimate = vec3(0.0);
    if (constants.cache.historyValid == 0) return false;
    SurfaceReprojection s = unpackReprojection(texelFetch(reprojection, q, 0).x, world);
    if (!s.found || texelFetch(historyCount, s.texel, 0).r == 0.0) return false;
    estimate = texelFetch(historyValue, s.texel, 0).rgb;
    return true;
}

// A neighbour on the pixel's surface: its estimate carried over to the pixel's normal, its
// directional sums (none where it was skipped) and its weight by how it faces.
struct Neighbour {
    vec3 value;
    vec4 sums;
    float weight;
    bool skipped;
};

// Neighbour q, `distance` pixels from the pixel (at p, normal n), where it lies on the pixel's
// surface: within 1.5 pixel footprints of its tangent plane per pixel of distance, facing within
// 60 degrees of it.
bool surfaceNeighbour(ivec2 q, float distance, vec3 p, vec3 n, float footprint,
                      float facingPower, out Neighbour s) {
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(frame.viewport.xy))))
        return false;
    vec4 estimate = texelFetch(estimates, q, 0);
    // Skipped, or background (stored alike; its reprojection finds nothing).
    s.skipped = wasSkipped(estimate);
    vec3 world = gbufferPosition(q).xyz;
    if (s.skipped && !skippedEstimate(q, world, estimate.rgb)) return false;
    vec3 delta = world - p;
    if (abs(dot(n, delta)) > 1.5 * footprint * max(1.0, distance)) return false;
    vec3 nq = texelFetch(gbufferNormal, q, 0).xyz;
    if (dot(n, nq) < 0.5) return false; // another face
    s.weight = pow(max(dot(n, nq), 0.0), facingPower);
    // A skipped neighbour has no directional sums: its value is carried over as it is, and adds
    // none to the next axis's.
    s.sums = s.skipped ? vec4(0.0) : texelFetch(directionals, q, 0);
    float toPixel =
        s.skipped ? 1.0 : min(directionalAt(s.sums, n) / directionalAt(s.sums, nq), 4.0);
    s.value = toPixel * estimate.rgb;
    return true;
}

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 axis = ivec2(constants.axisX, constants.axisY);
    // Only the x axis's directional sums are read (by the y axis); the y axis writes none.
    int reach = interleavedFilterReach(RADIUS, INTERLEAVE);
    // The x axis also filters the refresh tile's margin rows, which the y axis reads.
    int margin = axis.x == 1 ? reach : 0;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.viewport.xy);
    if (any(greaterThanEqual(pixel, size))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(filtered, pixel, vec4(0.0, 0.0, 0.0, 1.0));
        if (axis.x == 1) imageStore(filteredDirectional, pixel, vec4(0.0));
        return;
    }
    vec3 p = position.xyz;
    Reprojection history = reproject(pixel, p, constants.cache);
    if (convergedAround(pixel, history, constants.cache, margin)) {
        imageStore(filtered, pixel, vec4(0.0));
        if (axis.x == 1) imageStore(filteredDirectional, pixel, vec4(0.0));
        return;
    }
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    float footprint = 1.0 / pixelsPerUnit(viewDepth(p));
    // A pixel without history (the cache off, a first frame, a surface just revealed) has only
    // this frame's subsets: it weighs neighbours facing another way more (cos^4), for less
    // noise. Once its history holds a frame, the accumulation averages the subsets over frames
    // and the filter keeps to neighbours facing its own way (cos^8), which biases less.
    float facingPower = history.valid && history.count >= 1.0 ? 8.0 : 4.0;
    bool halfEnds = (2 * reach) % INTERLEAVE == 0;
    vec3 sum = vec3(0.0);
    vec4 directionalSum = vec4(0.0);
    float weightSum = 0.0, directionalWeight = 0.0;
    // Outward from the pixel, both sides at once. Past INTERLEAVE pixels (two of each subset
    // on the axis) the window ends where either side leaves the pixel's surface, so that it
    // stays symmetric about the pixel: a one-sided window at a crease or an edge averages
    // light from farther into the surface, which the symmetric one cancels to first order.
    // At the Cornell box's ceiling's crease with the back wall the one-sided mean was 1.4-2.2
    // times the reference; the frame's relMSE 0.0120 -> 0.0107 (docs/effects.md).
    for (int i = 0; i <= reach; ++i) {
        Neighbour side[2];
        bool found[2];
        found[0] = surfaceNeighbour(pixel - i * axis, float(i), p, n, footprint, facingPower,
                                    side[0]);
        found[1] = i > 0 && // the pixel itself, once
                   surfaceNeighbour(pixel + i * axis, float(i), p, n, footprint, facingPower,
                                    side[1]);
        if (i > INTERLEAVE && !(found[0] && found[1])) break;
        float end = halfEnds && i == reach ? 0.5 : 1.0;
        for (int k = 0; k < 2; ++k) {
            if (!found[k]) continue;
            float w = end * side[k].weight;
            sum += w * side[k].value;
            if (!side[k].skipped) {
                directionalSum += w * side[k].sums;
                directionalWeight += w;
            }
            weightSum += w;
        }
    }
    // The pixel's own estimate is always kept, so weightSum > 0.
    imageStore(filtered, pixel, vec4(sum / max(weightSum, 1e-6), 1.0));
    if (axis.x == 1)
        imageStore(filteredDirectional, pixel, directionalSum / max(directionalWeight, 1e-6));
}
