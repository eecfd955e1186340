#version 460
#extension GL_GOOGLE_include_directive : require
// Screen-space ambient occlusion: the fraction of the hemisphere (cosine-weighted) that is open
// within the AO radius. Three variants, chosen by specialization constant: the thesis's
// (equations 6-8), Crytek's depth-only sphere test (Mittring 2007), and a horizon-based
// estimate (GTAO, Jimenez et al. 2016) as the modern baseline.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int VARIANT = 0;
layout(constant_id = 1) const int DIRECTIONS = 8;
layout(constant_id = 2) const int STEPS = 4;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 4) uniform usampler2D reprojection;
layout(set = 0, binding = 5) uniform sampler2D historyCount;
layout(set = 0, binding = 6) uniform writeonly image2D aoImage; // r16f: the AO (r)
layout(push_constant) uniform AoBlock { AoConstants constants; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"

vec4 positionAt(vec2 pixel) { return gbufferPosition(ivec2(pixel)); }

#include "ao_thesis.glsl"
#include "ao_crytek.glsl"
#include "ao_horizon.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(aoImage, pixel, vec4(1.0));
        return;
    }
    vec3 p = position.xyz;
    if (converged(pixel, p, constants.cache)) {
        imageStore(aoImage, pixel, SCALAR_SKIPPED); // converged: the cache holds it
        return;
    }
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    float radius = constants.radius * constants.scale;
    float radiusPixels = radius * pixelsPerUnit(viewDepth(p));
    float rotation = pixelRotation(pixel) + constants.rotation;
    vec2 center = vec2(pixel) + 0.5;
    float visibility = 1.0;
    if (radiusPixels >= 1.0) {
        if (VARIANT == 0) visibility = thesisAo(center, p, n, radius, radiusPixels, rotation);
        if (VARIANT == 1) visibility = crytekAo(p, n, radius, rotation);
        if (VARIANT == 2) visibility = horizonAo(center, p, n, radius, radiusPixels, rotation);
    }
    // Not clamped at 1: a few of GTAO's slices give more than 1 where the normal leans (only
    // their mean over every slice's direction is 1 on an open plane), and the cache's mean of
    // frames clamped one by one was darker than the many-direction image (the Cornell box at 2
    // directions a frame, 72 frames: by 0.011 on average). The composite clamps the mean.
    imageStore(aoImage, pixel, vec4(vec3(max(visibility, 0.0)), 1.0));
}
