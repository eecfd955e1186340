#version 460
#extension GL_GOOGLE_include_directive : require
// world.insert (indirect_method 3): every pixel finds its own cell in the world cache
// (world_cache.glsl) or, where that is absent, a gathered cell one level coarser or finer at its
// point; else it makes its own in the first empty or evicted entry among its probes. It marks
// the cell used this frame, and a cell's pixels vote for the one whose point and normal it
// gathers at if it starts this frame (world.owner; world_schedule.comp takes them). Invocation 0
// also clears the next frame's row of counters.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3, r32ui) uniform coherent uimage2D worldKeys;
layout(set = 0, binding = 4, rgba32f) uniform image2D worldIrradiance;
layout(set = 0, binding = 5, r32ui) uniform uimage2D worldOwner;
layout(set = 0, binding = 6, r32ui) uniform uimage2D worldUsed;
layout(set = 0, binding = 7, r32ui) uniform coherent uimage2D worldStats;
layout(set = 0, binding = 8, rgba32f) uniform writeonly image2D worldDirections;
layout(push_constant) uniform WorldBlock { WorldConstants constants; };

#include "gbuffer_position.glsl"
#include "world_cache.glsl"

uint worldKeyAt(ivec2 e) {
    return imageLoad(worldKeys, e).r;
}
float worldSamplesAt(ivec2 e) {
    return imageLoad(worldIrradiance, e).a;
}

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    uint now = uint(frame.patternFrame);
    if (gl_GlobalInvocationID.xy == uvec2(0)) {
        // Row 2 keeps what this frame's world.schedule needs of the last frame's counters: the
        // cells live and the cells short of world_frames or new, and the refresh window moves on
        // by the width it had (world_schedule.comp). Then the last frame's row is cleared for
        // the next frame.
        int last = int(now + 1u) & 1;
        uint before = imageLoad(worldStats, ivec2(WORLD_STAT_SHORT, 2)).r;
        uint start = imageLoad(worldStats, ivec2(WORLD_STAT_WINDOW, 2)).r;
        imageStore(worldStats, ivec2(WORLD_STAT_WINDOW, 2),
                   uvec4((start + refreshSpan(before)) & 0xffffffu));
        imageStore(worldStats, ivec2(WORLD_STAT_SHORT, 2),
                   imageLoad(worldStats, ivec2(WORLD_STAT_SHORT, last)) +
                       imageLoad(worldStats, ivec2(WORLD_STAT_NEW, last)));
        imageStore(worldStats, ivec2(WORLD_STAT_LIVE, 2),
                   imageLoad(worldStats, ivec2(WORLD_STAT_LIVE, last)));
        for (int i = 0; i < WORLD_STATS; ++i)
            imageStore(worldStats, ivec2(i, last), uvec4(0u));
    }
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) return;
    vec3 p = position.xyz;
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    int level = worldLevel(distance(p, frame.cameraPosition.xyz));
    int direction = worldDirection(n);
    // The cell where it already is (its own, or a neighbouring level's: findPixelCell, the
    // lookup's rule too)...
    ivec2 found = findPixelCell(p, level, direction);
    // ...or its own, made in the first empty or evicted entry, which another pixel of the same
    // cell may take first (every pixel of a cell tries the same entries in the same order).
    WorldKey key = worldKey(worldCellOf(p, level), level, direction);
    for (int probe = 0; probe < WORLD_PROBES && found.x < 0; ++probe) {
        ivec2 entry = worldEntry(key.home, probe);
        uint seen = imageLoad(worldKeys, entry).r;
        if (seen == key.checksum) {
            found = entry; // made by another pixel this frame
        } else if (seen == WORLD_EMPTY || seen == WORLD_EVICTED) {
            uint held = imageAtomicCompSwap(worldKeys, entry, seen, key.checksum);
            if (held == seen) {
                imageStore(worldIrradiance, entry, vec4(0.0));
                imageStore(worldDirections, entry, vec4(0.0));
            }
            if (held == seen || held == key.checksum) found = entry;
        }
    }
    if (found.x >= 0) {
        if (imageLoad(worldUsed, found).r != now) imageStore(worldUsed, found, uvec4(now));
        // A starting cell's point is its pixel's nearest its centre, whichever thread runs
        // first, so that the same frame makes the same cells wherever they lie in the table.
        // Every frame votes: a cell restarted after an object moved takes its point anew.
        uint rank = ownerRank(pixel, ivec2(frame.viewport.xy), p, level);
        if (imageLoad(worldOwner, found).r < rank) imageAtomicMax(worldOwner, found, rank);
        return;
    }
    imageAtomicAdd(worldStats, ivec2(WORLD_STAT_FULL, int(now) & 1), 1u);
}
