#version 460
#extension GL_GOOGLE_include_directive : require
// world.upsample (indirect_method 3, world_half_res): the bounce world.lookup looked up at every
// other pixel brought to full resolution: each pixel interpolates the half-resolution samples
// on its surface around it (half_resolution.glsl). A pixel with none (an edge, thin geometry),
// or every pixel in a debug view, is listed for world.lookup_edges, which looks the cache up at
// those pixels alone: on lavapipe a branch costs every invocation of its SIMD row whether it is
// taken or not, so a lookup here, at the few pixels that need it, would cost as much as at all.
// With SKY, the sky's visibility the cells hold (world.sky_visibility_half) from the same
// samples.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const bool SKY = false; // the cells hold the sky's visibility

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D halfIndirect; // world.indirect_half
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D indirectImage;
layout(set = 0, binding = 5, r32ui) uniform uimage2D worldStats;
layout(set = 0, binding = 6, r32ui) uniform writeonly uimage2D edgeList; // world.edge_list
layout(set = 0, binding = 7) uniform sampler2D halfSky; // world.sky_visibility_half (SKY)
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D skyImage; // unwritten: !SKY
layout(push_constant) uniform WorldBlock { WorldConstants constants; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"
#include "half_resolution.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    int row = int(frame.patternFrame) & 1;
    if (gl_GlobalInvocationID.xy == uvec2(0)) { // world.lookup_edges' y and z workgroups
        imageStore(worldStats, ivec2(WORLD_STAT_EDGE_GROUPS + 1, row), uvec4(1u));
        imageStore(worldStats, ivec2(WORLD_STAT_EDGE_GROUPS + 2, row), uvec4(1u));
    }
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(indirectImage, pixel, vec4(0.0));
        if (SKY) imageStore(skyImage, pixel, vec4(1.0));
        return;
    }
    vec3 p = position.xyz;
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    // The samples within 6 pixels' footprints of p along its surface: seen at a grazing angle,
    // a pixel's step on the surface is longer than its footprint (up to 10 times), and the
    // bounce varies over a cell's width, which spans several pixels, not over a step. Their
    // normals within 10 degrees of n: each cell's light is carried to the pixel's own normal
    // (toNormal, world_lookup.glsl), so the bounce turns with the normal.
    vec3 toCamera = normalize(frame.cameraPosition.xyz - p);
    float stretch = 1.0 / max(abs(dot(n, toCamera)), 0.1);
    vec4 samples = compatibleHalfSamples(halfIndirect, textureSize(halfIndirect, 0), pixel, p, n,
                                         stretch, 0.985);
    if (samples.a > 0.0 && constants.work.w == WORLD_VIEW_LIGHT) {
        imageStore(indirectImage, pixel, vec4(samples.rgb / samples.a, 1.0));
        if (SKY) {
            // The same samples, weighed alike: where the bounce has one, so has the sky.
            vec4 sky = compatibleHalfSamples(halfSky, textureSize(halfSky, 0), pixel, p, n,
                                             stretch, 0.985);
            imageStore(skyImage, pixel, vec4(sky.rgb / sky.a, 1.0));
        }
        return;
    }
    uint slot = imageAtomicAdd(worldStats, ivec2(WORLD_STAT_EDGES, row), 1u);
    // world.lookup_edges' workgroups (64 invocations each), as many as the list needs.
    imageAtomicMax(worldStats, ivec2(WORLD_STAT_EDGE_GROUPS, row), slot / 64u + 1u);
    int width = int(frame.viewport.x);
    imageStore(edgeList, ivec2(int(slot) % width, int(slot) / width),
               uvec4(uint(pixel.x + pixel.y * width)));
}
