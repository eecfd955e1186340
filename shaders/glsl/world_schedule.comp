#version 460
#extension GL_GOOGLE_include_directive : require
// world.schedule (indirect_method 3): one invocation per entry of the world cache
// (world_cache.glsl), which decides what the cell does this frame. A cell no pixel used for
// table.z frames is evicted, or for two once the table is more than half full. A moved light or
// object restarts every cell in view and evicts the others: the RSM is drawn again, and every
// cell's VPLs and their visibility may have changed (keeping the cells away from a moved object, with their memory shortened, left the first
// frames after the move well above a fresh start's error, docs/stability.md). A live cell
// whose pixels offer a point much nearer its centre restarts too (retakes). A cell that starts
// this frame, made, restarted or retaken, takes its point and normal from the G-buffer at the
// pixel its pixels chose (world.owner). Then a cell is
// listed for world.gather (world_gather.comp) with the frames' worth of VPLs it gathers:
// - a new, restarted or retaken cell at once, world_new_cell_frames (at most world_frames): a camera cut,
//   and every frame without the cache (its table is cleared each frame), costs that;
// - an older cell with fewer than world_frames frames of samples, one, where it lies in this
//   frame's refresh window (refreshWindow: about world_cells_per_frame of them, the same ones
//   whichever order the threads run in);
// - a full one not at all: its value stands while the light and the objects stay still.
// The list (world.gather_list, as big as the table) holds entry + (frames << 22), its length in
// the counters' WORLD_STAT_LISTED and the gather's workgroups in WORLD_STAT_GROUPS (dispatched
// indirectly): the gather's invocations run over the cells that gather, side by side, rather
// than over a sparse table.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1, r32ui) uniform uimage2D worldKeys;
layout(set = 0, binding = 2, rgba32f) uniform image2D worldIrradiance;
layout(set = 0, binding = 3, rgba32f) uniform image2D worldPoints;
layout(set = 0, binding = 4) uniform usampler2D worldUsed;
layout(set = 0, binding = 5, r32ui) uniform coherent uimage2D worldStats;
layout(set = 0, binding = 6, r32ui) uniform writeonly uimage2D gatherList;
layout(set = 0, binding = 7, r32ui) uniform uimage2D worldOwner;
layout(set = 0, binding = 8) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 9) uniform sampler2D gbufferNormal;
layout(push_constant) uniform WorldBlock { WorldConstants constants; };

#include "gbuffer_position.glsl"
#include "world_cache.glsl"

// Whether a cell short of world_frames (its checksum `key`) refreshes this frame: a window of
// the cells' hashes, as wide as world_cells_per_frame over the cells short or new the frame
// before (refreshSpan), slides along them by its width each frame (world.insert moves it on:
// row 2 of the counters), so that every short cell refreshes in turn, and which ones do depends
// on the cells alone, not on the order the threads reach a counter. In 24-bit fixed point.
bool refreshWindow(uint key) {
    uint span = refreshSpan(imageLoad(worldStats, ivec2(WORLD_STAT_SHORT, 2)).r);
    uint start = imageLoad(worldStats, ivec2(WORLD_STAT_WINDOW, 2)).r;
    return (((worldHash(key) >> 8) - start) & 0xffffffu) < span;
}

// Whether the cell at `entry` (its checksum `key`) takes the point of the pixel its pixels
// chose this frame (`owner`) in place of its own: where that lies nearer the cell's centre
// than RETAKE times the distance its point does. The cell's level is the pixel's or one beside
// it (findPixelCell), the one whose key is the cell's. Each retake at least halves the
// distance, so a cell retakes a few times at most however the camera moves.
const float RETAKE = 0.5;
bool retakes(uint owner, uint key, ivec2 entry) {
    ivec2 pixel = ownerPixel(owner, ivec2(frame.viewport.xy));
    vec3 p = gbufferPosition(pixel).xyz;
    int direction = worldDirection(texelFetch(gbufferNormal, pixel, 0).xyz);
    int level = worldLevel(distance(p, frame.cameraPosition.xyz));
    for (int l = level - 1; l <= level + 1; ++l) {
        ivec3 cell = worldCellOf(p, l);
        if (worldKey(cell, l, direction).checksum != key) continue;
        vec3 centre = (vec3(cell) + 0.5) * worldCellSide(l);
        vec3 held = imageLoad(worldPoints, entry).xyz;
        return distance(p, centre) < RETAKE * distance(held, centre);
    }
    return false;
}

void main() {
    ivec2 entry = ivec2(gl_GlobalInvocationID.xy);
    uint now = uint(frame.patternFrame);
    if (entry == ivec2(0)) // the gather's z workgroups
        imageStore(worldStats, ivec2(WORLD_STAT_GROUPS + 2, int(now) & 1), uvec4(1u));
    if (any(greaterThanEqual(entry, imageSize(worldKeys)))) return;
    uint key = imageLoad(worldKeys, entry).r;
    if (key == WORLD_EMPTY || key == WORLD_EVICTED) return;
    loadPixelToWorld(); // pixel_to_world.glsl: after the empty entries, most of the table
    int row = int(now) & 1;
    // A moved light or object restarts every cell; one no pixel uses this frame is evicted
    // instead (its point may lie where the object was, and a cell out of sight would gather for
    // nothing): the pixels that come back to it make it anew.
    bool changed = constants.change.y > 0.0 || constants.change.z > 0.0;
    uint unused = now - texelFetch(worldUsed, entry, 0).r;
    // A table more than half full the frame before (row 2 of the counters, world_insert.comp)
    // keeps only the cells of the last two frames' views: past that load, a
    // key's probes find no free entry ever more often, and a moving camera's new cells, which
    // every pixel needs, would find none beside the ones it left, which no pixel needs.
    bool crowded = float(imageLoad(worldStats, ivec2(WORLD_STAT_LIVE, 2)).r) >
                   0.5 * float(constants.table.y);
    if (unused > uint(constants.table.z) || (crowded && unused > 1u) || (changed && unused != 0u)) {
        imageStore(worldKeys, entry, uvec4(WORLD_EVICTED)); // a tombstone (world_cache.glsl)
        // No samples: world.insert takes a cell's samples for its having been gathered before
        // this frame, and a cell made here this frame reads as none whichever pixel writes first.
        imageStore(worldIrradiance, entry, vec4(0.0));
        imageStore(worldOwner, entry, uvec4(WORLD_OWNERLESS));
        imageAtomicAdd(worldStats, ivec2(WORLD_STAT_EVICTED, row), 1u);
        return;
    }
    imageAtomicAdd(worldStats, ivec2(WORLD_STAT_LIVE, row), 1u);
    vec4 cell = imageLoad(worldIrradiance, entry);
    float frames = constants.cells.z;
    float count = changed ? 0.0 : cell.a;
    uint owner = imageLoad(worldOwner, entry).r;
    // A cell whose pixels offer a point much nearer its centre than the one it gathers at
    // starts again there (retakes): a view that saw only its edge (the screen's, or an
    // occluder's) chose the point, and the lookup takes its value for the centre's.
    if (count > 0.0 && owner != WORLD_OWNERLESS && retakes(owner, key, entry)) count = 0.0;
    if (count != cell.a) imageStore(worldIrradiance, entry, vec4(cell.rgb, count));
    // A cell that starts this frame (made, restarted or retaken) takes its point and normal from
    // the pixel its pixels chose: after an object moved, the old point may lie where it was.
    if (owner != WORLD_OWNERLESS) {
        if (count == 0.0) {
            ivec2 pixel = ownerPixel(owner, ivec2(frame.viewport.xy));
            imageStore(worldPoints, entry,
                       vec4(gbufferPosition(pixel).xyz,
                            packCellNormal(texelFetch(gbufferNormal, pixel, 0).xyz)));
        }
        imageStore(worldOwner, entry, uvec4(WORLD_OWNERLESS));
    }
    float gathered;
    if (count == 0.0) {
        gathered = min(constants.cells.w, frames);
        imageAtomicAdd(worldStats, ivec2(WORLD_STAT_NEW, row), 1u);
    } else if (count < frames) {
        imageAtomicAdd(worldStats, ivec2(WORLD_STAT_SHORT, row), 1u);
        if (!refreshWindow(key)) return;
        gathered = 1.0;
        imageAtomicAdd(worldStats, ivec2(WORLD_STAT_REFRESHED, row), 1u);
    } else {
        return;
    }
    uint slot = imageAtomicAdd(worldStats, ivec2(WORLD_STAT_LISTED, row), 1u);
    // The gather's workgroups of 64 cells, as many as the list needs, in rows of
    // WORLD_GATHER_GROUPS_X.
    uint group = slot / 64u;
    imageAtomicMax(worldStats, ivec2(WORLD_STAT_GROUPS, row), min(group + 1u, WORLD_GATHER_GROUPS_X));
    imageAtomicMax(worldStats, ivec2(WORLD_STAT_GROUPS + 1, row), group / WORLD_GATHER_GROUPS_X + 1u);
    uint index = uint(entry.x + entry.y * constants.table.x);
    imageStore(gatherList, worldTexel(slot), uvec4(index | (uint(gathered) << 22u)));
}
