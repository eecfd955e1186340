#version 460
#extension GL_GOOGLE_include_directive : require
// world.sky_visibility (indirect_method 3, world_sky_visibility): the sky's visibility beyond
// the screen (sky_visibility.glsl) held in the world cache's cells beside their bounce, like it
// a property of the surface point that no view changes. One invocation per cell world.schedule
// listed (world_schedule.comp), dispatched indirectly with world.gather's workgroups, before the
// gather: a cell that starts this frame (its samples still 0: made, or restarted after the light
// or an object moved, which draws the sky's maps again) computes it once, at the point and
// normal it gathers at; a refresh leaves it. world.lookup interpolates it between cells as it
// does the bounce.
#include "shared.h"
#include "common.glsl"
#include "sky_maps.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform usampler2D gatherList;
layout(set = 0, binding = 2, r32ui) uniform readonly uimage2D worldStats;
layout(set = 0, binding = 3) uniform sampler2D worldIrradiance;
layout(set = 0, binding = 4) uniform sampler2D worldPoints;
layout(set = 0, binding = 5) uniform sampler2D skyMaps; // depth atlas
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D worldSky;
layout(set = 0, binding = 7, std140) uniform TrianglesBlock { SkyTriangles exact; };
layout(set = 0, binding = 8, std140) uniform SkyBlock { WorldSky sky; };
layout(push_constant) uniform WorldBlock { WorldConstants constants; };

#include "world_cache.glsl"
#include "sky_visibility.glsl"

void main() {
    // The list's slot, as world.gather takes it.
    uint slot = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * 64u * WORLD_GATHER_GROUPS_X;
    int row = int(frame.patternFrame) & 1;
    if (slot >= imageLoad(worldStats, ivec2(WORLD_STAT_LISTED, row)).r) return;
    ivec2 entry = worldTexel(texelFetch(gatherList, worldTexel(slot), 0).r & 0x3fffffu);
    if (texelFetch(worldIrradiance, entry, 0).a != 0.0) return; // a refresh: it has its value
    vec4 point = texelFetch(worldPoints, entry, 0);
    vec3 visibility =
        skyVisibilityAt(point.xyz, unpackCellNormal(point.w), sky.maps, sky.reach.x, sky.reach.y);
    imageStore(worldSky, entry, vec4(visibility, 1.0));
}
