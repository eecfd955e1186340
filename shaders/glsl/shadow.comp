#version 460
#extension GL_GOOGLE_include_directive : require
// Soft shadows by percentage-closer filtering of the shadow map (thesis 3.4), with the kernel
// tied to the light's disk: a blocker search estimates the occluders' mean distance, and the
// penumbra a disk of that radius would cast (r (z_receiver - z_blocker) / z_blocker) sets the
// filter's size (percentage-closer soft shadows). One tap is the hard shadow test.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int TAPS = 49;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D shadowMap; // the light's depth (shadow_map_pass.cpp)
layout(set = 0, binding = 4) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 5) uniform sampler2D reprojection;
layout(set = 0, binding = 6) uniform sampler2D historyCount;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D shadowImage;
layout(push_constant) uniform ShadowBlock { ShadowConstants constants; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"

// The map's side in texels, read once in main(): the tap loops below use it at every tap.
float mapSize;

// Distance along the light's axis of the nearest surface the light sees through uv.
float occluderDepth(vec2 uv) {
    vec2 texel = clamp(uv * mapSize, vec2(0.0), vec2(mapSize - 1.0));
    float depth = texelFetch(shadowMap, ivec2(texel), 0).r;
    return linearDepth(depth, frame.lightFrustum.x, frame.lightFrustum.y);
}

// Distance along the light's axis at which the light's ray through the centre of uv's texel
// meets the receiver's plane (point p, normal n): comparing against it instead of p's own depth
// keeps a filter kernel on a sloped receiver from shadowing the receiver itself, and the texel's
// centre is where the map's depth was rasterised, so a flat receiver matches it exactly.
float receiverPlaneDepth(vec2 uv, vec3 p, vec3 n, float fallback) {
    uv = (floor(uv * mapSize) + 0.5) / mapSize;
    vec4 far = frame.inverseLightViewProjection * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
    vec3 dir = normalize(far.xyz / far.w - frame.lightPosition.xyz);
    float denom = dot(dir, n);
    if (abs(denom) < 1e-4) return fallback;
    float t = dot(p - frame.lightPosition.xyz, n) / denom;
    return t > 0.0 ? t * dot(dir, frame.lightDirection.xyz) : fallback;
}

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    mapSize = float(textureSize(shadowMap, 0).x);
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(shadowImage, pixel, vec4(1.0));
        return;
    }
    if (converged(pixel, position.xyz, constants.cache)) {
        imageStore(shadowImage, pixel, SKIPPED); // converged: the cache holds the value
        return;
    }
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
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
    float bias = receiver * texelAngle; // one texel of depth quantisation
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
        if (occluder + bias < receiverPlaneDepth(tap, p, n, receiver)) {
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
        lit += occluderDepth(tap) + bias >= receiverPlaneDepth(tap, p, n, receiver) ? 1.0 : 0.0;
    }
    imageStore(shadowImage, pixel, vec4(vec3(lit / float(TAPS)), 1.0));
}
