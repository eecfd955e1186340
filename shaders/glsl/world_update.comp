#version 460
#extension GL_GOOGLE_include_directive : require
// world.update (indirect_method 3): one invocation per entry of the world cache
// (world_cache.glsl). A cell no pixel used for table.z frames is evicted. A moved light
// restarts every cell; a moved object restarts the cells within a cell of its box (old and new
// place) and shortens every other cell's memory to a quarter of world_frames, since the VPLs it
// gathers from all changed a little. Then a cell gathers the bounce at its point:
// - a new or restarted cell at once, uncached world_frames frames' worth of VPLs, cached four;
// - an older cell with fewer than world_frames frames of samples, one frame's worth, while the
//   frame's refreshes (world_cells_per_frame) last;
// - a full one not at all: its value stands while the light and the objects stay still.
// A gather takes work.x VPLs a frame's worth from the flux's pool (indirect_vpls.comp: drawn in
// proportion to their flux, a new draw each frame when cached), a run from a place of its own
// for each cell and frame, each weighted by its probability, and tests each one's visibility
// through the voxel grid (world_voxels.glsl); its mean over the frames is the cell's value.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int POOL = 2048; // the flux's VPLs drawn this frame

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform usampler2D voxels;
layout(set = 0, binding = 2) uniform usampler2D voxelBlocks;
layout(set = 0, binding = 3) uniform sampler2D vplList;
layout(set = 0, binding = 4, r32ui) uniform uimage2D worldKeys;
layout(set = 0, binding = 5, rgba32f) uniform image2D worldIrradiance;
layout(set = 0, binding = 6) uniform sampler2D worldPoints;
layout(set = 0, binding = 7) uniform usampler2D worldUsed;
layout(set = 0, binding = 8, r32ui) uniform coherent uimage2D worldStats;
layout(push_constant) uniform WorldBlock { WorldConstants constants; };

#include "world_cache.glsl"
#include "world_voxels.glsl"

const float NEW_CELL_FRAMES = 4.0; // a new cell's first gather, in frames of samples (cached)

// Irradiance / pi at p (normal n) from `count` VPLs of the pool, from entry `start` on.
vec3 gather(vec3 p, vec3 n, int count, uint start) {
    float total = texelFetch(vplList, ivec2(POOL, 0), 0).r;
    if (total <= 0.0) return vec3(0.0);
    vec3 from = p + n * constants.cells.w;
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
        if (!voxelSegmentOpen(from, q + nq * constants.cells.w)) continue;
        sum += fluxProbability.rgb * (cosP * cosQ / (PI * PI * d2 * probability));
    }
    return sum / float(count);
}

bool nearMovedBox(vec3 p, float reach) {
    for (int i = 0; i < int(frame.motion.x); ++i) {
        vec3 lo = frame.movedBoxes[2 * i].xyz - reach, hi = frame.movedBoxes[2 * i + 1].xyz + reach;
        if (all(greaterThanEqual(p, lo)) && all(lessThanEqual(p, hi))) return true;
    }
    return false;
}

void main() {
    ivec2 entry = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(entry, imageSize(worldKeys)))) return;
    uint key = imageLoad(worldKeys, entry).r;
    if (key == 0u) return;
    uint now = uint(frame.patternFrame);
    int row = int(now) & 1;
    if (now - texelFetch(worldUsed, entry, 0).r > uint(constants.table.z)) {
        imageStore(worldKeys, entry, uvec4(0u));
        imageAtomicAdd(worldStats, ivec2(WORLD_STAT_EVICTED, row), 1u);
        return;
    }
    imageAtomicAdd(worldStats, ivec2(WORLD_STAT_LIVE, row), 1u);
    vec4 cell = imageLoad(worldIrradiance, entry);
    vec4 point = texelFetch(worldPoints, entry, 0);
    vec3 p = point.xyz;
    vec3 n = octahedralDecode(unpackSnorm2x16(floatBitsToUint(point.w)));
    float frames = constants.cells.z;
    float count = cell.a;
    if (constants.change.y > 0.0) count = 0.0;
    if (constants.change.z > 0.0) {
        float side = worldCellSide(worldLevel(distance(p, frame.cameraPosition.xyz)));
        count = nearMovedBox(p, side) ? 0.0 : min(count, max(1.0, floor(frames / 4.0)));
    }
    float gathered;
    if (count == 0.0) {
        gathered = constants.table.w != 0 ? min(NEW_CELL_FRAMES, frames) : frames;
        imageAtomicAdd(worldStats, ivec2(WORLD_STAT_NEW, row), 1u);
    } else if (count < frames &&
               imageAtomicAdd(worldStats, ivec2(WORLD_STAT_BUDGET, row), 1u) <
                   uint(constants.work.y)) {
        gathered = 1.0;
        imageAtomicAdd(worldStats, ivec2(WORLD_STAT_REFRESHED, row), 1u);
    } else {
        if (count != cell.a) imageStore(worldIrradiance, entry, vec4(cell.rgb, count));
        return;
    }
    uint index = uint(entry.x + entry.y * constants.table.x);
    uint start = worldHash(index * 9781u + now * 6271u);
    vec3 value = gather(p, n, int(gathered) * constants.work.x, start);
    vec3 mean = (cell.rgb * count + value * gathered) / (count + gathered);
    imageStore(worldIrradiance, entry, vec4(mean, min(count + gathered, frames)));
}
