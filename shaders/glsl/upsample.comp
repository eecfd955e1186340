#version 460
#extension GL_GOOGLE_include_directive : require
// Half-resolution indirect light to full resolution (thesis ch. 4): each pixel interpolates
// bilinearly among the four surrounding half-res samples whose G-buffer position and normal
// are close to its own; a pixel with no such neighbour (an edge, thin geometry) gathers its
// VPLs at full resolution instead. A converged pixel is skipped: its cache holds it.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int VPLS = 512;
layout(constant_id = 1) const int VISIBILITY = 1;
layout(constant_id = 2) const int VISIBILITY_STEPS = 6;
layout(constant_id = 3) const int HALF_RES = 1; // 0: no half-res gather, every pixel gathers
layout(constant_id = 4) const int PEELING = 0; // the visibility test between two depth layers
layout(constant_id = 5) const int LIGHT_CHECK = 1; // the visibility test asks the light's map

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform usampler2D rsmVpls; // rsm_vpl.glsl
layout(set = 0, binding = 4) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 5) uniform usampler2D reprojection;
layout(set = 0, binding = 6) uniform sampler2D historyCount;
layout(set = 0, binding = 7) uniform sampler2D halfIndirect;
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D indirectImage;
layout(set = 0, binding = 9) uniform sampler2D secondLayer; // peel.position (PEELING only)
layout(set = 0, binding = 10) uniform sampler2D lightDepthMin; // light_depth_min (LIGHT_CHECK only)
layout(push_constant) uniform IndirectBlock { IndirectConstants constants; };

#include "gbuffer_position.glsl"
#include "rsm_vpl.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"
#include "indirect_gather.glsl"
#include "half_resolution.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(indirectImage, pixel, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    vec3 p = position.xyz;
    if (converged(pixel, p, constants.cache)) {
        imageStore(indirectImage, pixel, vec4(0.0));
        return;
    }
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    // Half-res samples skipped this frame are not used (half_resolution.glsl).
    ivec2 halfSize = ivec2(constants.width, constants.height);
    vec4 samples = HALF_RES != 0
                       ? compatibleHalfSamples(halfIndirect, halfSize, pixel, p, n, 1.0, 0.9)
                       : vec4(0.0);
    if (samples.a > 0.0) {
        imageStore(indirectImage, pixel, vec4(samples.rgb / samples.a, 1.0));
    } else {
        vec4 unused; // the directional sums serve the interleaved method alone
        vec3 e = gatherIndirect(p, n, pixelRotation(pixel) + constants.rotation,
                                constants.scale, constants.radius,
                                radialOffset(constants.radialOffset, 0.5), 0, 1, unused);
        imageStore(indirectImage, pixel, vec4(e, 1.0));
    }
}
