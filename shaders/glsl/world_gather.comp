#version 460
#extension GL_GOOGLE_include_directive : require
// world.gather (indirect_method 3): one invocation per cell that world.schedule listed
// (world_schedule.comp), over the whole list's capacity: the invocations past its length return
// at once. A cell gathers work.x VPLs for each frame's worth it was given from the flux's pool
// (indirect_vpls.comp: drawn in proportion to their flux, a new draw each frame when cached), a
// run from a place of its own for each cell and frame (from its key's hash), each weighted by
// its probability, tests each one's visibility through the voxel grid (world_voxels.glsl), and
// blends the estimate into the cell's mean by the frames' worth on each side.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 64) in;
layout(constant_id = 0) const int POOL = 2048; // the flux's VPLs drawn this frame

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform usampler2D voxels;
layout(set = 0, binding = 2) uniform usampler2D voxelBlocks;
layout(set = 0, binding = 3) uniform sampler2D vplList;
layout(set = 0, binding = 4, rgba32f) uniform image2D worldIrradiance;
layout(set = 0, binding = 5) uniform sampler2D worldPoints;
layout(set = 0, binding = 6) uniform usampler2D worldStats;
layout(set = 0, binding = 7) uniform usampler2D gatherList;
layout(set = 0, binding = 8) uniform usampler2D worldKeys;
layout(push_constant) uniform WorldBlock { WorldConstants constants; };

#include "world_cache.glsl"
#include "world_voxels.glsl"

// Irradiance / pi at p (normal n) from `count` VPLs of the pool, from entry `start` on.
vec3 gather(vec3 p, vec3 n, int count, uint start) {
    float total = texelFetch(vplList, ivec2(POOL, 0), 0).r;
    if (total <= 0.0) return vec3(0.0);
    // Half a voxel off each surface (world_voxels.glsl leaves the surfaces' own voxels).
    float offset = 0.5 * frame.worldGridOrigin.w;
    vec3 from = p + n * offset;
    // A VPL of the VPL map stands for a texel of it: its footprint's half-width per distance from
    // the light, squared.
    float footprint = frame.lightFrustum.z * frame.lightFrustum.z * constants.change.x;
    vec3 sum = vec3(0.0);
    for (int j = 0; j < count; ++j) {
        int k = int((start + uint(j)) % uint(POOL));
        vec4 position = texelFetch(vplList, ivec2(k, 0), 0);
        vec4 fluxProbability = texelFetch(vplList, ivec2(k, 2), 0);
        float probability = fluxProbability.w;
        if (probability <= 0.0) continue;
        vec3 q = position.xyz;
        vec3 nq = texelFetch(vplList, ivec2(k, 1), 0).xyz;
        vec3 toVpl = q - p;
        float distance2 = dot(toVpl, toVpl);
        vec3 D = toVpl * inversesqrt(max(distance2, 1e-30));
        float cosP = dot(n, D), cosQ = -dot(nq, D);
        if (cosP <= 0.0 || cosQ <= 0.0) continue;
        // The distance clamped to the VPL's footprint, as the other methods clamp it.
        vec3 fromLight = q - frame.lightPosition.xyz;
        float d2 = max(distance2, dot(fromLight, fromLight) * footprint);
        if (!voxelSegmentOpen(from, q + nq * offset)) continue;
        sum += fluxProbability.rgb * (cosP * cosQ / (PI * PI * d2 * probability));
    }
    return sum / float(count);
}

void main() {
    uint slot = gl_GlobalInvocationID.x;
    uint now = uint(frame.patternFrame);
    if (slot >= texelFetch(worldStats, ivec2(WORLD_STAT_LISTED, int(now) & 1), 0).r) return;
    uint listed = texelFetch(gatherList,
                             ivec2(slot % uint(constants.table.x), slot / uint(constants.table.x)),
                             0).r;
    uint index = listed & 0x3fffffu;
    float gathered = float(listed >> 22u);
    ivec2 entry = ivec2(index % uint(constants.table.x), index / uint(constants.table.x));
    vec4 cell = imageLoad(worldIrradiance, entry);
    vec4 point = texelFetch(worldPoints, entry, 0);
    vec3 n = octahedralDecode(unpackSnorm2x16(floatBitsToUint(point.w)));
    // Where its run of VPLs starts: from its key rather than its entry, so that a cell gathers the
    // same wherever a collision put it.
    uint start = worldHash(texelFetch(worldKeys, entry, 0).r + now * 6271u);
    vec3 value = gather(point.xyz, n, int(gathered) * constants.work.x, start);
    float count = cell.a;
    vec3 mean = (cell.rgb * count + value * gathered) / (count + gathered);
    imageStore(worldIrradiance, entry, vec4(mean, min(count + gathered, constants.cells.z)));
}
