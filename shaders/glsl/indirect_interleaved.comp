#version 460
#extension GL_GOOGLE_include_directive : require
// One-bounce indirect light with interleaved sampling (Keller and Heidrich 2001; Segovia et al.
// 2006): every pixel gathers, at full resolution, one of INTERLEAVE^2 disjoint subsets of the
// pattern's VPLS virtual point lights, the one its place in an INTERLEAVE x INTERLEAVE block
// names (shared_vpls.h vplSubset). A pixel so pays 1/INTERLEAVE^2 of the VPLs, and every block
// gathers each VPL once; indirect_reconstruct.comp then gives each pixel the whole set's
// estimate from its neighbours on the same surface. Beside its irradiance / pi each pixel
// writes the directional sums of its VPLs' light (indirect_gather.glsl), with which the filter
// carries a neighbour's estimate over to the pixel's own normal. A converged pixel is skipped
//: its cache holds it.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int VPLS = 512;
layout(constant_id = 1) const int VISIBILITY = 1;
layout(constant_id = 2) const int VISIBILITY_STEPS = 6;
layout(constant_id = 3) const int INTERLEAVE = 4;
layout(constant_id = 4) const int RADIUS = 8; // the filter's, for the refresh tile's margin
layout(constant_id = 5) const int PEELING = 0; // the visibility test between two depth layers
layout(constant_id = 6) const int LIGHT_CHECK = 1; // the visibility test asks the light's map

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform usampler2D rsmVpls; // rsm_vpl.glsl
layout(set = 0, binding = 4) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 5) uniform usampler2D reprojection;
layout(set = 0, binding = 6) uniform sampler2D historyCount;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D interleavedIndirect;
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D interleavedDirectional;
layout(set = 0, binding = 9) uniform sampler2D secondLayer; // peel.position (PEELING only)
layout(set = 0, binding = 10) uniform sampler2D lightDepthMin; // light_depth_min (LIGHT_CHECK only)
layout(push_constant) uniform IndirectBlock { IndirectConstants constants; };

#include "gbuffer_position.glsl"
#include "rsm_vpl.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"
#include "indirect_gather.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    // The refresh tile is computed with a margin as wide as the filter's two axes reach.
    int margin = interleavedFilterReach(RADIUS, INTERLEAVE);
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(interleavedIndirect, pixel, vec4(0.0));
        imageStore(interleavedDirectional, pixel, vec4(0.0));
        return;
    }
    if (convergedAround(pixel, position.xyz, constants.cache, margin)) {
        imageStore(interleavedIndirect, pixel, SKIPPED);
        imageStore(interleavedDirectional, pixel, SKIPPED);
        return;
    }
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    // Cached, the subsets also turn frame by frame (a low-discrepancy sequence over the frame
    // index), so that over frames every pixel gathers every subset; a single frame keeps its
    // place's own.
    int subsets = INTERLEAVE * INTERLEAVE;
    int turn = constants.radialOffset < 0.0 ? 0 : int(fract(frame.patternFrame * 0.618034) * float(subsets));
    int subset = (vplSubset(pixel.x, pixel.y, INTERLEAVE) + turn) % subsets;
    vec4 directional;
    vec3 e = gatherIndirect(position.xyz, n, pixelRotation(pixel) + constants.rotation,
                            constants.scale, constants.radius,
                            radialOffset(constants.radialOffset, 0.5),
                            subset, INTERLEAVE, directional);
    imageStore(interleavedIndirect, pixel, vec4(e, 1.0));
    imageStore(interleavedDirectional, pixel, directional);
}
