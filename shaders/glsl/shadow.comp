#version 460
#extension GL_GOOGLE_include_directive : require
// The share of the spot light's disk each G-buffer pixel sees, from the shadow map, in one of
// two ways (shadow_variant):
//   0  percentage-closer soft shadows (thesis 3.4): a blocker search estimates the occluders'
//      mean distance, the penumbra a disk of that radius would cast (r (z_receiver - z_blocker)
//      / z_blocker) sets the size of a percentage-closer filter.
//   1  light-space horizons (docs/effects.md): the disk seen from p, direction by direction,
//      with each map texel taken as a solid from the map's depth to its back faces' depth.
// One tap (shadow_taps = 1) is the hard shadow test in either.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int TAPS = 49;      // shadow_taps (PCSS's filter)
layout(constant_id = 1) const int VARIANT = 1;    // shadow_variant
layout(constant_id = 2) const int DIRECTIONS = 12; // shadow_directions (horizons)
layout(constant_id = 3) const int STEPS = 6;       // shadow_steps (horizons)

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D shadowMap; // the light's depth (shadow_map_pass.cpp)
// The depth of the nearest surface facing away from the light (variant 1; else the map again).
layout(set = 0, binding = 4) uniform sampler2D shadowMapBack;
layout(set = 0, binding = 5) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 6) uniform usampler2D reprojection;
layout(set = 0, binding = 7) uniform sampler2D historyCount;
layout(set = 0, binding = 8) uniform sampler2D historyValue; // last frame's blended shadow (r)
layout(set = 0, binding = 9) uniform writeonly image2D shadowImage; // r16f: the shadow (r)
layout(push_constant) uniform ShadowBlock { ShadowConstants constants; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"

// The maps' sides in texels, read once in main(): the tap loops below use them at every tap.
float mapSize, backMapSize;

// Distance along the light's axis of the depth `map` (side `size`) holds through uv.
float depthAlongAxis(sampler2D map, float size, vec2 uv) {
    vec2 texel = clamp(uv * size, vec2(0.0), vec2(size - 1.0));
    float depth = texelFetch(map, ivec2(texel), 0).r;
    return linearDepth(depth, frame.lightFrustum.x, frame.lightFrustum.y);
}

// Distance along the light's axis of the nearest surface the light sees through uv.
float occluderDepth(vec2 uv) { return depthAlongAxis(shadowMap, mapSize, uv); }

// Distance along the light's axis of the nearest back face through uv (the far plane if none).
float backDepth(vec2 uv) { return depthAlongAxis(shadowMapBack, backMapSize, uv); }

// The receiver's plane (point p, normal n) as the light sees it: along the light's ray through
// NDC point x, the distance along its axis to the plane is 1 / (c.x + c.y x.x + c.z x.y), its
// inverse affine in x as a plane's is under a perspective projection. Set once per pixel.
vec3 receiverPlane;

void setReceiverPlane(vec3 p, vec3 n) {
    // The ray's direction through NDC x, scaled to a unit step along the light's axis: affine
    // in x, since the far plane's points are.
    vec3 rays[3];
    const vec2 ndc[3] = vec2[3](vec2(0.0), vec2(1.0, 0.0), vec2(0.0, 1.0));
    for (int i = 0; i < 3; ++i) {
        vec4 far = frame.inverseLightViewProjection * vec4(ndc[i], 1.0, 1.0);
        vec3 ray = far.xyz / far.w - frame.lightPosition.xyz;
        rays[i] = ray / dot(ray, frame.lightDirection.xyz);
    }
    float height = dot(p - frame.lightPosition.xyz, n);
    vec3 c = vec3(dot(rays[0], n), dot(rays[1] - rays[0], n), dot(rays[2] - rays[0], n));
    receiverPlane = abs(height) > 1e-12 ? c / height : vec3(0.0);
}

// Distance along the light's axis at which the light's ray through the centre of uv's texel
// meets the receiver's plane (setReceiverPlane): comparing against it instead of p's own depth
// keeps a filter kernel on a sloped receiver from shadowing the receiver itself, and the texel's
// centre is where the map's depth was rasterised, so a flat receiver matches it exactly.
// `fallback` where the ray does not meet the plane ahead of the light.
float receiverPlaneDepth(vec2 uv, float fallback) {
    vec2 x = (floor(uv * mapSize) + 0.5) / mapSize * 2.0 - 1.0;
    float inverse = receiverPlane.x + receiverPlane.y * x.x + receiverPlane.z * x.y;
    return inverse > 1e-12 ? 1.0 / inverse : fallback;
}

// Light-space horizons. In the map, a point at depth z (along the light's axis) and angular
// offset a from p's texel (tan units: lateral distance / z) lies on the segment from p (depth
// z_r) to the point of the disk at lateral offset s from its centre only if a points along s,
// and then at 1/z = 1/z_r + |a| / |s|. A column of the map taken as solid from its depth z_f to
// its back faces' depth z_b therefore blocks, along a's direction, the disk's points at radii
//     |a| / (1/z_f - 1/z_r)  <=  |s|  <=  |a| / (1/z_b - 1/z_r)
// (no upper bound where z_b lies beyond p). The disk's radii are kept as 32 bins of equal area
// (bin i: (r/R)^2 in [i/32, (i+1)/32)), one bit each, so the blocked ranges of all of a
// direction's columns add up without counting a radius twice.

// The angular offset of sample k of `steps` along a direction, from `first` out to `reach`:
// denser near p, where contacts need them.
float horizonSample(int k, int steps, float first, float reach, float ring) {
    float t = (float(k) + ring) / float(steps);
    return first + (reach - first) * t * t;
}

// The bins [x, y) blocked by a column seen between angular offsets aLo and aHi, solid from
// `front` to `back`, from a receiver at depth `receiver`; invR2 = 1 / R^2.
ivec2 blockedBins(float aLo, float aHi, float front, float back, float receiver, float invR2) {
    float invFront = 1.0 / front - 1.0 / receiver;
    if (invFront <= 0.0) return ivec2(0); // not nearer the light than p
    float invBack = 1.0 / back - 1.0 / receiver;
    float uLo = aLo * aLo / (invFront * invFront) * invR2;
    float uHi = invBack > 0.0 ? aHi * aHi / (invBack * invBack) * invR2 : 1.0;
    return ivec2(clamp(ivec2(vec2(uLo, uHi) * 32.0 + 0.5), ivec2(0), ivec2(32)));
}

uint binBits(ivec2 bins) {
    if (bins.y <= bins.x) return 0u;
    uint ones = bins.y - bins.x >= 32 ? 0xffffffffu : (1u << uint(bins.y - bins.x)) - 1u;
    return ones << uint(bins.x);
}

// The share of the disk p sees (p at uv and depth `receiver`; its plane in receiverPlane). Each
// direction starts from its own point within a texel of p's (a percentage-closer filter's
// smallest kernel, which antialiases the map's texels) and tests that point's own column, then
// STEPS columns out to where blockers a fifth of p's distance from the light would still reach
// the disk. Where two successive columns both block, the radii between their ranges are blocked
// too: the surface is taken to run on between them, as a ray march takes a depth buffer's to.
float horizonShare(vec2 uv, float receiver, float bias, float texelAngle, float rotation,
                   float ring) {
    float tanHalf = frame.lightFrustum.z;
    float radius = max(frame.lightPosition.w, tinyLength());
    float invR2 = 1.0 / (radius * radius);
    float first = 1.5 * texelAngle;
    float reach = max(4.0 * radius / receiver, 2.0 * first);
    int steps = STEPS; // not const: a const copy left the module without STEPS by name
    float a0 = horizonSample(0, steps, first, reach, ring);
    int unblocked = 0;
    for (int d = 0; d < DIRECTIONS; ++d) {
        float theta = rotation + (float(d) + 0.5) * 2.0 * PI / float(DIRECTIONS);
        vec2 dir = vec2(cos(theta), sin(theta)) / (2.0 * tanHalf); // uv per angular unit
        vec2 origin = uv + vogelDisk(d, DIRECTIONS, rotation + 1.0, ring) / mapSize;
        uint blocked = 0u;
        ivec2 previous = ivec2(0); // the last column's bins; empty where it did not block
        float front = occluderDepth(origin);
        if (front + bias < receiverPlaneDepth(origin, receiver)) {
            previous = blockedBins(0.0, 0.5 * a0, front, backDepth(origin), receiver, invR2);
            blocked = binBits(previous);
        }
        float a = a0, aBefore = 0.0;
        for (int k = 0; k < steps; ++k) {
            float aAfter = horizonSample(k + 1, steps, first, reach, ring);
            vec2 tap = origin + dir * a;
            front = occluderDepth(tap);
            ivec2 bins = ivec2(0);
            if (front + bias < receiverPlaneDepth(tap, receiver))
                bins = blockedBins(0.5 * (aBefore + a), 0.5 * (a + aAfter), front, backDepth(tap),
                                   receiver, invR2);
            if (bins.y > bins.x) {
                ivec2 filled = bins;
                if (previous.y > previous.x)
                    filled = ivec2(min(bins.x, previous.y), max(bins.y, previous.x));
                blocked |= binBits(filled);
            }
            previous = bins;
            aBefore = a;
            a = aAfter;
        }
        unblocked += bitCount(~blocked);
    }
    return float(unblocked) / float(32 * DIRECTIONS);
}

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    mapSize = float(textureSize(shadowMap, 0).x);
    backMapSize = float(textureSize(shadowMapBack, 0).x);
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(shadowImage, pixel, vec4(1.0));
        return;
    }
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    Reprojection history = reproject(pixel, position.xyz, constants.cache);
    bool reuse = convergedAround(pixel, history, constants.cache, 0);
    if (reuse && !cameraMoved()) {
        imageStore(shadowImage, pixel, SCALAR_SKIPPED); // converged: the cache holds it
        return;
    }
    // The light's disk wholly behind p's tangent plane: p sees none of it, whatever stands in
    // between, and the direct light there is 0 however lit (direct.comp spotIrradiance). The
    // disk's farthest point in front of the plane lies its radius times the normal's part
    // across the light's axis beyond its centre.
    vec3 axis = frame.lightDirection.xyz;
    float ahead = dot(n, frame.lightPosition.xyz - position.xyz) +
                  frame.lightPosition.w * length(n - dot(n, axis) * axis);
    if (ahead <= 0.0) {
        imageStore(shadowImage, pixel, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    // Normal-offset lookup, scaled by the cosine at which the light meets the surface. The
    // receiver's depth is compared at each texel's centre, where the map's depth was rasterised
    // (receiverPlaneDepth), so a flat receiver needs no offset at any slope; what the offset is
    // for is a curved or faceted one, whose shading normal's plane is not the surface the map
    // holds. Where the light grazes, a full offset lifts the lookup far off the surface across
    // the light's rays, out of the shadow of what stands on it: Sponza's gallery walls, lit at
    // 81 degrees from their normal, took a 5.4 cm offset, which moves a shadow's edge along
    // them by 5.4 / tan(9 degrees) = 34 cm; scaled by the cosine, Sponza's one frame went from
    // relMSE 0.0386 to 0.0125 against the path tracer (docs/ground-truth.md).
    float texelAngle = 2.0 * frame.lightFrustum.z / mapSize;
    float texelAtP = distance(position.xyz, frame.lightPosition.xyz) * texelAngle;
    float cosLight = abs(dot(n, normalize(frame.lightPosition.xyz - position.xyz)));
    vec3 p = position.xyz + n * (constants.normalOffset * texelAtP * cosLight);
    vec4 clip = frame.lightViewProjection * vec4(p, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (clip.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) {
        imageStore(shadowImage, pixel, vec4(0.0, 0.0, 0.0, 1.0)); // outside the light's cone
        return;
    }
    float receiver = clip.w;
    setReceiverPlane(p, n);
    float bias = receiver * texelAngle; // one texel of depth quantisation
    // While the camera moves, a value reused was computed at the history's texels around p, not
    // at p: a shadow thinner than their spacing (a thin blocker's, a needle's) can fall between
    // them, all lit, and onto p. The map's one texel at p's own point says whether the light's
    // centre is blocked there; a value that says the opposite (lit where the centre is
    // blocked, or dark where it is seen) is computed again.
    if (reuse) {
        float kept = texelFetch(historyValue, history.texel, 0).r;
        bool centreBlocked = occluderDepth(uv) + bias < receiverPlaneDepth(uv, receiver);
        if (centreBlocked ? kept <= 0.75 : kept >= 0.25) {
            imageStore(shadowImage, pixel, SCALAR_SKIPPED);
            return;
        }
    }
    float rotation = pixelRotation(pixel) + constants.rotation;
    float ring = radialOffset(constants.radialOffset, 0.5);

    // The hard test (one tap: no kernel to carry a leak along the surface) keeps the full
    // offset and compares the pixel's own depth, as before the scaling: against the point
    // light, the scaled offset left grazing walls in self-shadow (test_reference's
    // DirectLightOfAPointLight: 619 pixels more than 10% off, 31 with the full offset).
    if (TAPS == 1) {
        vec4 lifted = frame.lightViewProjection *
                      vec4(position.xyz + n * (constants.normalOffset * texelAtP), 1.0);
        vec2 liftedUv = lifted.xy / lifted.w * 0.5 + 0.5;
        float lit = lifted.w <= occluderDepth(liftedUv) + bias ? 1.0 : 0.0;
        imageStore(shadowImage, pixel, vec4(vec3(lit), 1.0));
        return;
    }

    if (VARIANT == 1) {
        float lit = horizonShare(uv, receiver, bias, texelAngle, rotation, ring);
        imageStore(shadowImage, pixel, vec4(vec3(lit), 1.0));
        return;
    }

    // Blocker search: the disk seen from the receiver, as far as blockers at a fifth of the
    // receiver's distance, in shadow-map uv; at least a few texels so PCF still antialiases.
    float uvPerUnit = 1.0 / (2.0 * frame.lightFrustum.z * receiver);
    float lightRadius = frame.lightPosition.w;
    float maxRadius = 48.0 / mapSize;
    float minRadius = 1.5 / mapSize;
    float searchRadius = clamp(4.0 * lightRadius * uvPerUnit, minRadius, maxRadius);
    float blockerSum = 0.0;
    int blockers = 0;
    for (int i = 0; i < TAPS; ++i) {
        vec2 tap = uv + vogelDisk(i, TAPS, rotation, ring) * searchRadius * constants.scale;
        float occluder = occluderDepth(tap);
        if (occluder + bias < receiverPlaneDepth(tap, receiver)) {
            blockerSum += occluder;
            ++blockers;
        }
    }
    if (blockers == 0) {
        imageStore(shadowImage, pixel, vec4(1.0));
        return;
    }
    float blocker = blockerSum / float(blockers);
    float penumbra = lightRadius * max(receiver - blocker, 0.0) / max(blocker, tinyLength());
    float filterRadius = clamp(penumbra * uvPerUnit, minRadius, maxRadius);
    float lit = 0.0;
    for (int i = 0; i < TAPS; ++i) {
        vec2 tap = uv + vogelDisk(i, TAPS, rotation, ring) * filterRadius * constants.scale;
        lit += occluderDepth(tap) + bias >= receiverPlaneDepth(tap, receiver) ? 1.0 : 0.0;
    }
    imageStore(shadowImage, pixel, vec4(vec3(lit / float(TAPS)), 1.0));
}
