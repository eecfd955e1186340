#version 460
#extension GL_GOOGLE_include_directive : require
// One-bounce indirect light gathered from the RSM's VPLs at half resolution: each half-res
// pixel computes at the G-buffer sample of its 2x2 block's top-left pixel.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int VPLS = 512;
layout(constant_id = 1) const int VISIBILITY = 1;
layout(constant_id = 2) const int VISIBILITY_STEPS = 6;
layout(constant_id = 3) const int PEELING = 0; // the visibility test between two depth layers
layout(constant_id = 4) const int LIGHT_CHECK = 1; // the visibility test asks the light's map

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform usampler2D rsmVpls; // rsm_vpl.glsl
layout(set = 0, binding = 4) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 5) uniform usampler2D reprojection;
layout(set = 0, binding = 6) uniform sampler2D historyCount;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D halfIndirect;
layout(set = 0, binding = 8) uniform sampler2D secondLayer; // peel.position (PEELING only)
layout(set = 0, binding = 9) uniform sampler2D lightDepthMin; // light_depth_min (LIGHT_CHECK only)
layout(push_constant) uniform IndirectBlock { IndirectConstants constants; };

#include "gbuffer_position.glsl"
#include "rsm_vpl.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"
#include "indirect_gather.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(constants.width, constants.height)))) return;
    ivec2 source = pixel * 2;
    // Skipped when every full-resolution pixel of the block is converged.
    bool allConverged = true;
    for (int j = 0; j < 4 && allConverged; ++j) {
        ivec2 q = min(source + ivec2(j & 1, j >> 1), ivec2(frame.viewport.xy) - 1);
        vec4 w = gbufferPosition(q);
        allConverged = w.w == 0.0 ||
                       converged(q, w.xyz, constants.cache);
    }
    if (allConverged) {
        imageStore(halfIndirect, pixel, SKIPPED);
        return;
    }
    vec4 position = gbufferPosition(source);
    vec3 result = vec3(0.0);
    if (position.w != 0.0) {
        vec3 n = texelFetch(gbufferNormal, source, 0).xyz;
        vec4 unused; // the directional sums serve the interleaved method alone
        result = gatherIndirect(position.xyz, n, pixelRotation(pixel) + constants.rotation,
                                constants.scale, constants.radius,
                                radialOffset(constants.radialOffset, 0.5), 0, 1, unused);
    }
    imageStore(halfIndirect, pixel, vec4(result, 1.0));
}
