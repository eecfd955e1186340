// The world cache's hash table (indirect_method 3). A cell is a cube of world space at one level
// of size (worldLevel: growing with the distance from the camera) and one of
// six normal directions (the normal's dominant axis and its sign), so that the two sides of a
// wall, or a floor and the ceiling above it, never share a cell. Its key is a 32-bit checksum of
// those; it lives at its home entry, a second hash of them, or one of the WORLD_PROBES entries
// after it (open addressing with linear probing). An entry holds a checksum, WORLD_EMPTY (never
// taken since the table was cleared) or WORLD_EVICTED (a tombstone: a cell was evicted there).
// A key lies before the first empty entry of its probes, so a lookup stops at one; an insert
// takes the first empty or evicted entry, and an evicted cell leaves a tombstone rather than a
// hole, which would hide the keys after it. The table's images hold entry i at texel
// (i % table.x, i / table.x):
//   world.keys       R32UI    the checksum, WORLD_EMPTY or WORLD_EVICTED
//   world.irradiance RGBA32F  rgb: irradiance / pi at the cell's point (the mean of its
//                             gathers), a: the frames of samples behind it (0: none yet)
//   world.points     RGBA32F  xyz: the point it gathers at (its pixel nearest its centre), w: its
//                             normal (packCellNormal: a whole number, so that every texel is one)
//   world.directions RGBA32F  the mean of its gathers' light as an L1 spherical harmonic of its
//                             luminance (world_gather.comp), to carry its value to other normals
//   world.used       R32UI    the last frame a pixel used it (FrameUniforms.patternFrame)
//   world.owner      R32UI    which of this frame's pixels may give the cell its point: the
//                             largest of its pixels' ownerRank (the one whose point lies
//                             nearest the cell's centre, whichever thread runs first),
//                             WORLD_OWNERLESS where no pixel used it; world.schedule takes the point from it where the
//                             cell starts (new or restarted) and empties it for the next frame
// Needs: constants (WorldConstants), common.glsl.
#ifndef SSGI_WORLD_CACHE_GLSL
#define SSGI_WORLD_CACHE_GLSL

const int WORLD_PROBES = 16;
const uint WORLD_EMPTY = 0u;
const uint WORLD_EVICTED = 1u;
const uint WORLD_OWNERLESS = 0u;
// The width of the refresh window (world_schedule.comp), in 24-bit fixed point (1 << 24: every
// cell): world_cells_per_frame over `candidates`, the cells short of world_frames or new the
// frame before.
uint refreshSpan(uint candidates) {
    float width =
        candidates > 0u ? min(1.0, float(constants.work.y) / float(candidates)) : 1.0;
    return uint(width * 16777216.0);
}

// A PCG hash (O'Neill 2014).
uint worldHash(uint v) {
    v = v * 747796405u + 2891336453u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    return (v >> 22u) ^ v;
}

// The level of the cells at distance d from the camera: level l's cells are 2^l scene units wide
// (l may be negative), the power of two nearest below d times world_cell_angle, so that a cell
// spans about the same angle from the camera near and far (and its side follows the scene's
// scale).
int worldLevel(float d) {
    return clamp(int(floor(log2(max(d * constants.cells.x, 1e-30)))), -120, 120);
}
float worldCellSide(int level) {
    return exp2(float(level));
}
// 0..5: +x, -x, +y, -y, +z, -z, the normal's dominant axis.
int worldDirection(vec3 n) {
    vec3 a = abs(n);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
    return 2 * axis + (n[axis] < 0.0 ? 1 : 0);
}

struct WorldKey {
    uint home;     // the first entry it may take
    uint checksum; // 2 or more
};
WorldKey worldKey(ivec3 cell, int level, int direction) {
    uint tag = uint(level * 6 + direction);
    WorldKey k;
    k.home = worldHash(uint(cell.x) + worldHash(uint(cell.y) + worldHash(uint(cell.z) +
                                                                          worldHash(tag)))) &
             uint(constants.table.y - 1);
    // Another hash of the same four numbers, so that keys that share a home differ here; never
    // WORLD_EMPTY or WORLD_EVICTED.
    k.checksum = max(worldHash(uint(cell.x) * 73856093u ^ uint(cell.y) * 19349663u ^
                               uint(cell.z) * 83492791u ^ (tag + 1u) * 2654435761u),
                     2u);
    return k;
}
// Entry i's texel in the table's images. The table's width and its entries are powers of two
// (world_cache_pass.cpp), so that this and the hashes' modulo are masks and shifts: a division
// by a number not known when the shader is compiled is many times slower on a CPU device.
ivec2 worldTexel(uint i) {
    return ivec2(i & uint(constants.table.x - 1), i >> uint(findLSB(constants.table.x)));
}
ivec2 worldEntry(uint home, int probe) {
    return worldTexel((home + uint(probe)) & uint(constants.table.y - 1));
}
// A normal as one float: its octahedral map in 12 bits per axis, a whole number below 2^24 that
// a float holds exactly (a float of arbitrary bits may be a NaN).
float packCellNormal(vec3 n) {
    uvec2 q = uvec2(round((octahedralEncode(n) * 0.5 + 0.5) * 4095.0));
    return float(q.x + q.y * 4096u);
}
vec3 unpackCellNormal(float packed) {
    uint v = uint(packed);
    return octahedralDecode(vec2(v & 4095u, v >> 12u) / 4095.0 * 2.0 - 1.0);
}

// The cell that holds p at `level` (in cells of that level).
ivec3 worldCellOf(vec3 p, int level) {
    return ivec3(floor(p / worldCellSide(level)));
}

// A pixel's claim to give its cell (at `level`) its point: larger for a point nearer the cell's
// centre, then for a pixel earlier in the image. The lookup interpolates a cell's value as the
// value at its centre (world_lookup.glsl), and the point nearest it is nearly the same from any
// view, so that a cell made while the camera moved holds what a still camera would have made
// (the first pixel in the image's order would lie on the cell's edge, and move with the view).
// The rank holds the distance, quantized,
// above the pixel's index in the bits the image's pixels need.
int ownerIndexBits(ivec2 size) {
    return findMSB(uint(size.x * size.y)) + 1;
}
uint ownerRank(ivec2 pixel, ivec2 size, vec3 p, int level) {
    int bits = ownerIndexBits(size);
    uint mask = (1u << bits) - 1u;
    float side = worldCellSide(level);
    vec3 centre = (vec3(worldCellOf(p, level)) + 0.5) * side;
    float d = min(distance(p, centre) / (0.8660254 * side), 1.0); // 1: a corner
    uint steps = (1u << min(32 - bits, 16)) - 1u;
    uint near = steps - uint(d * float(steps));
    return (near << bits) | (mask - uint(pixel.x + pixel.y * size.x));
}
ivec2 ownerPixel(uint rank, ivec2 size) {
    uint mask = (1u << ownerIndexBits(size)) - 1u;
    uint index = mask - (rank & mask);
    return ivec2(index % uint(size.x), index / uint(size.x));
}

// What a shader that finds cells defines, reading the table through the binding it has
// (world.insert's storage images, world.lookup's samplers): entry e's key, and its frames of
// samples (world.irradiance's a).
uint worldKeyAt(ivec2 e);
float worldSamplesAt(ivec2 e);

// The entry holding the key, or (-1, -1): a key lies before the first empty entry.
ivec2 findCell(WorldKey key) {
    for (int probe = 0; probe < WORLD_PROBES; ++probe) {
        uint held = worldKeyAt(worldEntry(key.home, probe));
        if (held == key.checksum) return worldEntry(key.home, probe);
        if (held == WORLD_EMPTY) break;
    }
    return ivec2(-1);
}

// The cell a pixel at p with the normal's `direction` takes, world.insert's and world.lookup's
// one rule: its own at `level`, or where that is absent, the cell one level coarser, else one
// finer, at p that an earlier frame gathered (world_level_reuse: a camera moving nearer or
// further would otherwise remake a surface's cells each time its distance crosses a power of
// two), `level` then becoming that cell's; (-1, -1) where none is (world.insert makes its own).
ivec2 findPixelCell(vec3 p, inout int level, int direction) {
    ivec2 own = findCell(worldKey(worldCellOf(p, level), level, direction));
    for (int step = 0; step < 2 && own.x < 0 && constants.cells.y != 0.0; ++step) {
        int other = level + (step == 0 ? 1 : -1);
        ivec2 entry = findCell(worldKey(worldCellOf(p, other), other, direction));
        if (entry.x >= 0 && worldSamplesAt(entry) > 0.0) {
            own = entry;
            level = other;
        }
    }
    return own;
}

#endif
