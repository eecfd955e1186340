// The voxel occupancy grid of indirect_method 3 (world_voxelize.frag writes it), in blocks of
// 4 x 4 x 4 voxels (WORLD_BLOCK; blocks per axis gridSize / 4 rounded up):
// - voxels: a block's 64 voxels as 64 bits in two R32UI texels, block b's at texels
//   (2 (b.x + blocks along x * b.z) + 0 or 1, b.y); voxel v's bit is v's place in its block,
//   x + 4 y + 16 z, the second texel holding z 2 and 3 (voxelWord, voxelBit);
// - for each block the distance to the nearest occupied one (world_voxel_distance.comp), in
//   blocks along the farthest axis, at texel (x + blocks along x * z, y) of an R8UI image.
// Its test of a segment walks every voxel the segment crosses in an occupied block (Amanatides
// and Woo 1987), so a wall one voxel thick stops it, with the block's two words read once, and
// crosses the cube of empty blocks around an empty block in one step.
// The grid's place and size are the frame's (FrameUniforms.worldGridOrigin, worldGridSize).
// Needs: frame; for the test, usampler2D voxels and voxelDistance. With WORLD_VOXELS_LAYOUT_ONLY
// defined, the layout alone (for the passes that write the grid, whose images are storage
// images).
#ifndef SSGI_WORLD_VOXELS_GLSL
#define SSGI_WORLD_VOXELS_GLSL

ivec3 blockCount() {
    return (frame.worldGridSize.xyz + WORLD_BLOCK - 1) / WORLD_BLOCK;
}
// The texel of block b's first word; its second is the next texel.
ivec2 blockTexel(ivec3 b) {
    return ivec2(2 * (b.x + blockCount().x * b.z), b.y);
}
// Which of its block's two words holds voxel v's bit (0 or 1), and the bit.
int voxelWord(ivec3 v) {
    return (v.z & 3) >> 1;
}
uint voxelBit(ivec3 v) {
    ivec3 local = v & 3;
    return 1u << uint(local.x + 4 * local.y + 16 * (local.z & 1));
}
ivec2 distanceTexel(ivec3 b) {
    return ivec2(b.x + blockCount().x * b.z, b.y);
}

#ifndef WORLD_VOXELS_LAYOUT_ONLY
// 0 for an occupied block, else d: every block within d - 1 of b (along each axis) is empty.
int blockDistance(ivec3 b) {
    return int(texelFetch(voxelDistance, distanceTexel(b), 0).r);
}

// Where a ray from A along unit `dir` (1 / dir: `inverse`) leaves the box [lo, lo + side].
float boxExit(vec3 A, vec3 inverse, vec3 lo, float side) {
    vec3 far = (lo + side * step(0.0, inverse) - A) * inverse;
    return min(far.x, min(far.y, far.z));
}

// The voxel a walk from A along `dir` is in just past distance s (the walk's steps end on voxel
// faces; a thousandth of a voxel on is inside the next), kept in the grid.
ivec3 voxelAfter(vec3 A, vec3 dir, float s) {
    return clamp(ivec3(floor(A + dir * (s + 1e-3))), ivec3(0), frame.worldGridSize.xyz - 1);
}

// What voxelSegment finds of a segment.
const int SEGMENT_BLOCKED = 0;
const int SEGMENT_OPEN = 1;
const int SEGMENT_UNKNOWN = 2; // the walk stopped before its end (a loop limit): nothing known

// Whether the segment from a to b (world space) crosses an occupied voxel (SEGMENT_BLOCKED) or
// none (SEGMENT_OPEN). Both ends lie on surfaces, in voxels the surfaces occupy: the walk leaves
// the voxels it starts in while they are occupied (its own surface), and takes the occupied
// voxels within two voxels of b for b's own surface.
int voxelSegment(vec3 a, vec3 b) {
    vec3 A = (a - frame.worldGridOrigin.xyz) / frame.worldGridOrigin.w;
    vec3 B = (b - frame.worldGridOrigin.xyz) / frame.worldGridOrigin.w;
    float len = length(B - A);
    if (len < 1e-6) return SEGMENT_OPEN;
    vec3 dir = (B - A) / len;
    // No component exactly 0: a ray along a grid plane never leaves it through that axis.
    dir = mix(dir, vec3(1e-7), lessThan(abs(dir), vec3(1e-7)));
    vec3 inverse = 1.0 / dir;
    // The part of the segment inside the grid.
    vec3 size = vec3(frame.worldGridSize.xyz);
    vec3 t0 = (vec3(0.0) - A) * inverse, t1 = (size - A) * inverse;
    float s = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
    float end = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), len));
    bool leaving = true;
    // A step's length at least a thousandth of a voxel, so that the walk always moves on.
    for (int i = 0; i < 4096 && s < end; ++i) {
        ivec3 v = voxelAfter(A, dir, s);
        ivec3 block = v / WORLD_BLOCK;
        int empty = blockDistance(block) - 1; // the radius of the cube of empty blocks around
        if (empty >= 0) {
            leaving = false;
            s = boxExit(A, inverse, vec3((block - empty) * WORLD_BLOCK),
                        float((2 * empty + 1) * WORLD_BLOCK)) +
                1e-3;
            continue;
        }
        ivec2 texel = blockTexel(block);
        uvec2 words = uvec2(texelFetch(voxels, texel, 0).r,
                            texelFetch(voxels, texel + ivec2(1, 0), 0).r);
        // The block's voxels one by one, until the walk leaves it.
        for (; s < end && i < 4096; ++i) {
            float exit = boxExit(A, inverse, vec3(v), 1.0);
            if ((words[voxelWord(v)] & voxelBit(v)) != 0u) {
                if (!leaving && len - exit > 2.0) return SEGMENT_BLOCKED;
            } else {
                leaving = false;
            }
            s = exit + 1e-3;
            v = voxelAfter(A, dir, s);
            if (v / WORLD_BLOCK != block) break;
        }
    }
    return s >= end ? SEGMENT_OPEN : SEGMENT_UNKNOWN;
}

#endif // WORLD_VOXELS_LAYOUT_ONLY

#endif
