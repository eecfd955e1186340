// The voxel occupancy grid of indirect_method 3 (world_voxelize.frag writes it), at two levels:
// - voxels: one bit a voxel, 32 voxels along x to a word, the word of voxel (x, y, z) at texel
//   (x / 32 + voxelWords() z, y) of an R32UI image;
// - blocks: one bit for each 4 x 4 x 4 voxels, set where any of them is occupied, laid out the
//   same way (blockWords(), blocks per axis gridSize / 4 rounded up).
// Its test of a segment walks every voxel the segment crosses (Amanatides and Woo 1987), so a
// wall one voxel thick stops it, and crosses an empty block in one step.
// The grid's place and size are the frame's (FrameUniforms.worldGridOrigin, worldGridSize).
// Needs: frame; for the test, usampler2D voxels and voxelBlocks. With WORLD_VOXELS_LAYOUT_ONLY
// defined, the layout alone (for the pass that writes the grid, whose images are storage images).
#ifndef SSGI_WORLD_VOXELS_GLSL
#define SSGI_WORLD_VOXELS_GLSL

int voxelWords() {
    return (frame.worldGridSize.x + 31) / 32;
}
ivec3 blockCount() {
    return (frame.worldGridSize.xyz + WORLD_BLOCK - 1) / WORLD_BLOCK;
}
int blockWords() {
    return (blockCount().x + 31) / 32;
}
// The texel holding voxel v's bit, and the bit.
ivec2 voxelTexel(ivec3 v) {
    return ivec2((v.x >> 5) + voxelWords() * v.z, v.y);
}
ivec2 blockTexel(ivec3 b) {
    return ivec2((b.x >> 5) + blockWords() * b.z, b.y);
}
uint voxelBit(int x) {
    return 1u << uint(x & 31);
}

#ifndef WORLD_VOXELS_LAYOUT_ONLY
bool voxelOccupied(ivec3 v) {
    return (texelFetch(voxels, voxelTexel(v), 0).r & voxelBit(v.x)) != 0u;
}
bool blockOccupied(ivec3 b) {
    return (texelFetch(voxelBlocks, blockTexel(b), 0).r & voxelBit(b.x)) != 0u;
}

// Where a ray from A along unit `dir` (1 / dir: `inverse`) leaves the box [lo, lo + side].
float boxExit(vec3 A, vec3 inverse, vec3 lo, float side) {
    vec3 far = (lo + side * step(0.0, inverse) - A) * inverse;
    return min(far.x, min(far.y, far.z));
}

// Whether the segment from a to b (world space) crosses no occupied voxel. Both ends lie on
// surfaces, in voxels the surfaces occupy: the walk leaves the voxels it starts in while they
// are occupied (its own surface), and takes the occupied voxels within two voxels of b for b's
// own surface.
bool voxelSegmentOpen(vec3 a, vec3 b) {
    vec3 A = (a - frame.worldGridOrigin.xyz) / frame.worldGridOrigin.w;
    vec3 B = (b - frame.worldGridOrigin.xyz) / frame.worldGridOrigin.w;
    float len = length(B - A);
    if (len < 1e-6) return true;
    vec3 dir = (B - A) / len;
    // No component exactly 0: a ray along a grid plane never leaves it through that axis.
    dir = mix(dir, vec3(1e-7), lessThan(abs(dir), vec3(1e-7)));
    vec3 inverse = 1.0 / dir;
    // The part of the segment inside the grid.
    vec3 size = vec3(frame.worldGridSize.xyz);
    vec3 t0 = (vec3(0.0) - A) * inverse, t1 = (size - A) * inverse;
    float s = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
    float end = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), len));
    ivec3 last = frame.worldGridSize.xyz - 1;
    bool leaving = true;
    // A step's length at least a thousandth of a voxel, so that the walk always moves on.
    for (int i = 0; i < 4096 && s < end; ++i) {
        vec3 P = A + dir * (s + 1e-3);
        ivec3 v = clamp(ivec3(floor(P)), ivec3(0), last);
        ivec3 block = v / WORLD_BLOCK;
        if (!blockOccupied(block)) {
            leaving = false;
            s = boxExit(A, inverse, vec3(block * WORLD_BLOCK), float(WORLD_BLOCK)) + 1e-3;
            continue;
        }
        float exit = boxExit(A, inverse, vec3(v), 1.0);
        if (voxelOccupied(v)) {
            if (!leaving && len - exit > 2.0) return false;
        } else {
            leaving = false;
        }
        s = exit + 1e-3;
    }
    return true;
}

#endif // WORLD_VOXELS_LAYOUT_ONLY

#endif
