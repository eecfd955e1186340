#version 460
#extension GL_GOOGLE_include_directive : require
// world.voxel_distance_x, _y, _z (indirect_method 3): for each 4 x 4 x 4 block of the voxel grid,
// how far the nearest occupied block lies, in blocks along the farthest axis (the Chebyshev
// distance), at most WORLD_DISTANCE_CAP: 0 in an occupied block, d where every block within
// d - 1 of it is empty. The visibility test (world_voxels.glsl) crosses such a cube of empty
// blocks in one step. The distance is separable, one pass an axis (AXIS), each reading the last:
// - x: from the voxels (`source` is world.voxels), the distance along the block's row;
// - y: from x's (`source`), the farthest-axis distance within the block's xy-plane;
// - z: from y's (`source`), the whole distance.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int AXIS = 0;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform usampler2D source;
layout(set = 0, binding = 2, r8ui) uniform writeonly uimage2D distanceOut;

#define WORLD_VOXELS_LAYOUT_ONLY
#include "world_voxels.glsl"

uint sourceAt(ivec3 b) {
    if (AXIS == 0) {
        ivec2 texel = blockTexel(b);
        uint any = texelFetch(source, texel, 0).r | texelFetch(source, texel + ivec2(1, 0), 0).r;
        return any != 0u ? 0u : WORLD_DISTANCE_CAP;
    }
    return texelFetch(source, distanceTexel(b), 0).r;
}

void main() {
    ivec3 count = blockCount();
    // One invocation a block: x along the image's width, y and z along its height.
    ivec3 b = ivec3(gl_GlobalInvocationID.x, gl_GlobalInvocationID.y % uint(count.y),
                    gl_GlobalInvocationID.y / uint(count.y));
    if (any(greaterThanEqual(b, count))) return;
    // The nearest along AXIS whose own distance (0 for an occupied block in the x pass) leaves
    // the farthest axis's distance smallest; blocks outside the grid are empty.
    uint nearest = WORLD_DISTANCE_CAP;
    for (int k = -int(WORLD_DISTANCE_CAP) + 1; k < int(WORLD_DISTANCE_CAP); ++k) {
        ivec3 c = b;
        c[AXIS] += k;
        if (c[AXIS] < 0 || c[AXIS] >= count[AXIS]) continue;
        nearest = min(nearest, max(uint(abs(k)), sourceAt(c)));
    }
    imageStore(distanceOut, distanceTexel(b), uvec4(nearest));
}
