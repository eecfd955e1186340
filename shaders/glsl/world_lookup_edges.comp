#version 460
#extension GL_GOOGLE_include_directive : require
// world.lookup_edges (indirect_method 3, world_half_res): the bounce looked up in the world cache
// (world_lookup.glsl) at the pixels world.upsample listed (world.edge_list: those with no
// half-resolution sample on their surface, or every pixel in a debug view), one invocation per
// pixel, dispatched indirectly for the list's length; with SKY, the sky's visibility too.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 64) in;
layout(constant_id = 0) const bool SKY = false; // the cells hold the sky's visibility

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform usampler2D worldKeys;
layout(set = 0, binding = 4) uniform sampler2D worldIrradiance;
layout(set = 0, binding = 5) uniform usampler2D worldUsed;
layout(set = 0, binding = 6) uniform sampler2D worldPoints;
layout(set = 0, binding = 7) uniform sampler2D worldDirections;
layout(set = 0, binding = 8) uniform sampler2D worldSky;
layout(set = 0, binding = 9) uniform usampler2D worldStats;
layout(set = 0, binding = 10) uniform usampler2D edgeList; // world.edge_list
layout(set = 0, binding = 11, rgba16f) uniform writeonly image2D indirectImage;
layout(set = 0, binding = 12, rgba16f) uniform writeonly image2D skyImage; // unwritten: !SKY
layout(push_constant) uniform WorldBlock { WorldConstants constants; };

#include "gbuffer_position.glsl"
#include "world_cache.glsl"
#include "world_lookup.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    int row = int(frame.patternFrame) & 1;
    uint slot = gl_GlobalInvocationID.x;
    if (slot >= texelFetch(worldStats, ivec2(WORLD_STAT_EDGES, row), 0).r) return;
    int width = int(frame.viewport.x);
    uint index = texelFetch(edgeList, ivec2(int(slot) % width, int(slot) / width), 0).r;
    ivec2 pixel = ivec2(int(index) % width, int(index) / width);
    vec3 p = gbufferPosition(pixel).xyz;
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    vec4 sky;
    imageStore(indirectImage, pixel, worldLookup(p, n, constants.work.w, sky));
    if (SKY) imageStore(skyImage, pixel, sky);
}
