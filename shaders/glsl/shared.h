// Structures shared by C++ and GLSL: one declaration, compiled by both. The uniform block's
// members are only vec4, mat4 and ivec4, so that std140 lays them out exactly as C++ does; push
// constants (std430) may also hold int and float scalars. The static_asserts hold the C++ side
// to the sizes the shaders expect.
#ifndef SSGI_SHARED_H
#define SSGI_SHARED_H

#ifdef __cplusplus
#include <cmath>
#include <glm/glm.hpp>
namespace ssgi::shader {
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using mat4 = glm::mat4;
using ivec4 = glm::ivec4;
using uint = glm::uint;
using glm::clamp;
using glm::floatBitsToUint;
using glm::uintBitsToFloat;
using glm::length;
using glm::max;
using glm::mix;
using glm::step;
using std::asinh;
using std::cos;
using std::exp;
using std::floor;
using std::pow;
using std::sin;
using std::sinh;
#define SSGI_CHECK_SIZE(type, bytes) static_assert(sizeof(type) == bytes, #type " layout")
#define SSGI_INLINE inline
#define SSGI_OUT(type) type&
#else
#define SSGI_CHECK_SIZE(type, bytes)
#define SSGI_INLINE
#define SSGI_OUT(type) out type
#endif

// Lengths below this fraction of the scene's diagonal (FrameUniforms.sceneDiagonal) count as
// zero where a shader divides by one (screen_space.glsl tinyLength): a floor relative to the
// scene, so that its units do not change the image.
#define SCENE_TINY 1e-6f

// Everything a pass may need about the frame: cameras, the light, the sky. Set 0, binding 0.
struct FrameUniforms {
    mat4 view;
    mat4 projection;
    mat4 viewProjection;
    mat4 inverseViewProjection;
    mat4 previousViewProjection;
    // The G-buffer holds a view depth d per pixel, not a position (gbuffer_position.glsl): this
    // maps (x d, y d, d, 1), for the pixel centre (x, y) in pixels, to the world position there.
    // Last frame's maps its history's texels (at its size, which a resize changes).
    mat4 pixelToWorld;
    mat4 previousPixelToWorld;
    mat4 lightViewProjection;
    // The same for the RSM's texels and their distance along the light's axis (rsm_vpl.glsl):
    // the RSM keeps no positions.
    mat4 lightPixelToWorld;
    mat4 inverseLightViewProjection;
    vec4 cameraPosition; // xyz
    vec4 lightPosition;  // xyz, w = disk radius
    vec4 lightDirection; // xyz unit axis, w = cos(outer cone half-angle)
    vec4 lightColor;     // rgb = colour * intensity (W/sr on the axis), w = cos(inner half-angle)
    vec4 lightFrustum;   // x = near, y = far, z = tan(half fov), w = shadow-map size in texels
    vec4 skyZenith;      // rgb radiance
    vec4 skyHorizon;
    vec4 skyGround;
    vec4 viewport;       // x = width, y = height, z = 1/width, w = 1/height
    float exposure;      // multiplies the radiance before tone mapping
    float patternFrame;  // where the sampling patterns stand: RenderOptions::patternStart + frame
    float sceneDiagonal; // length of the scene's bounding box's diagonal (world units)
    float cameraMoved;   // 1 where viewProjection differs from previousViewProjection, else 0
    // Objects that moved since the last frame: box i spans movedBoxes[2i].xyz..movedBoxes[2i+1].xyz
    // (world space, old and new place together); motion.x = number of boxes (at most 4).
    vec4 movedBoxes[8];
    vec4 motion;
    // x = the power of two every light, sky and so every radiance in the intermediate images is
    // divided by, so that a very bright scene fits their half floats (65504 at most); 1 for the
    // usual scene. The composite multiplies it back.
    vec4 radianceScale;
    // The world cache's voxel grid (indirect_method 3; world_grid.h), placed anew when the light
    // or an object moves: xyz its lowest corner, w a voxel's side; xyz voxels per axis, w the
    // most along any axis (world_voxels, what its images hold).
    vec4 worldGridOrigin;
    ivec4 worldGridSize;
};
SSGI_CHECK_SIZE(FrameUniforms, 10 * 64 + 22 * 16);

// Per draw in the raster passes (push constants).
struct DrawConstants {
    mat4 model;
    vec4 baseColorFactor;
    // x = 1 when a base-colour texture is bound, y = alpha cutoff (0 = opaque), z = 1 when the
    // vertex colours multiply the base colour
    vec4 material;
};
SSGI_CHECK_SIZE(DrawConstants, 96);

// What an object that moved restarts in a cache (CacheConstants.motionTest; EffectCache).
#define MOTION_RESTART_ALL 0 // the whole history: the renderer resets it
#define MOTION_NEAR_BOX 1    // the pixels within motionReach of a moved box (occlusion)
#define MOTION_LIGHT_PATH 2  // the pixels whose path to the light passes within motionReach of one

// What the reprojection does beyond the thesis (CacheConstants.reprojection): where the camera
// moved the screen's edges across the radius the effect gathers within, start over. (The
// reprojection pass's own test, thin geometry included, is ReprojectionConstants'.)
#define REPROJECT_SCREEN_EDGE 2
// What is reused beyond the thesis (CacheConstants.reprojection, with the REPROJECT_ flags):
// while the camera moves, a pixel whose history holds one computation or more is reused until
// its resampling blur reaches the effect's budget (temporal.glsl convergedAround).
#define REUSE_WHILE_MOVING 4
// A view-independent effect's value (CachedEffect::viewIndependent) whose history texels agree
// is resampled without blur: kept while the camera moves (temporal.comp historyAt).
#define REUSE_AGREEING 8

// The display transform, per colour channel: Narkowicz's fit of the ACES filmic curve of
// exposed linear radiance, then the sRGB encoding. The composite applies it on the GPU; the
// programs that show a linear image the same way (reference --png, compare's and the golden
// tests' display images, the stability panels) apply it on the CPU.
SSGI_INLINE float tonemapAces(float x) {
    return clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}
SSGI_INLINE float encodeSrgb(float linear) {
    return mix(linear * 12.92f, 1.055f * pow(linear, 1.0f / 2.4f) - 0.055f,
               step(0.0031308f, linear));
}

// How far the interleaved indirect light's filter reaches along each axis, in pixels: its
// radius, and at least across the k x k block of VPL subsets (indirect_reconstruct.comp). The
// refresh tile is widened by as much, so that its pixels find their neighbours computed.
SSGI_INLINE int interleavedFilterReach(int radius, int interleave) {
    return max(radius, interleave / 2);
}

// The reprojection pass's image (R32UI; reprojection.glsl packReprojection): one word holds, in
// its bits 0 to 11 and 12 to 23, where the surface lay in last frame's image within its texel
// along x and y, in REPROJECTION_SUBTEXELs of a texel; in bits 24 to 27 the offset of the texel
// that holds the surface from the one the point lies in, (dx + 1) + 3 (dy + 1) + 1, or 0 where
// none does; in bits 28 to 31 the bilinear footprint. The whole texels follow from the pixel's
// world position (reprojection.glsl unpackReprojection).
#define REPROJECTION_SUBTEXEL 4096
#define REPROJECTION_FRACTION_BITS 12
#define REPROJECTION_OFFSET_SHIFT 24
#define REPROJECTION_FOOTPRINT_SHIFT 28

// A cache's count texel (R8_UNORM, one byte; cache.h kCountFormat): the rotations accumulated
// at a pixel (0: it holds nothing) in its low 7 bits, as half steps up to CACHE_COUNT_HALVES and
// whole ones above, to CACHE_COUNT_MAX (cache_rotations' largest value), and in bit 7 whether
// the temporal pass asked for it to be computed next frame (reuse while moving). A count between
// steps (a blend's effective number of samples where the blur budget cut the history's weight) is
// rounded down, so that a pixel never counts more samples than its blend holds; the counts the
// cache writes as such (0, a resize's half sample, whole counts, an exact effect's 1.5) are steps.
// A due pixel holds one computation or more, so code 0 always means "nothing".
#define CACHE_COUNT_HALVES 32
#define CACHE_COUNT_MAX 95
#define CACHE_COUNT_DUE 128
SSGI_INLINE float countCode(float count, bool due) {
    float c = count < float(CACHE_COUNT_MAX) ? count : float(CACHE_COUNT_MAX);
    // The 1/1000 absorbs float rounding of a blend that is a whole number of samples.
    float steps = c <= float(CACHE_COUNT_HALVES) ? floor(2.0f * c + 1e-3f)
                                                 : float(CACHE_COUNT_HALVES) + floor(c + 1e-3f);
    return steps + (due ? float(CACHE_COUNT_DUE) : 0.0f);
}
SSGI_INLINE float countOfCode(float code) {
    float steps = code >= float(CACHE_COUNT_DUE) ? code - float(CACHE_COUNT_DUE) : code;
    return steps <= float(2 * CACHE_COUNT_HALVES) ? 0.5f * steps
                                                  : steps - float(CACHE_COUNT_HALVES);
}
SSGI_INLINE bool dueOfCode(float code) {
    return code >= float(CACHE_COUNT_DUE);
}

// The composite's HDR output (`hdr`, RG32UI): R, G and B as 21-bit floats, a float's sign,
// exponent and 12 of its 23 mantissa bits, R in x's bits 0-20, G in x's bits 21-31 and y's 0-9,
// B in y's 10-30: a float's range (an EXR keeps what half floats cannot hold), infinities and
// NaNs included, to within 1/4096 of the value. Rounded to odd (the last kept bit set where any
// dropped one is), so that the half float the EXR stores where the image fits one (image_io.cpp)
// is the float's own nearest half, as if nothing had been dropped on the way.
#define HDR_DROPPED_BITS 11
SSGI_INLINE uint hdrBits(float v) {
    uint bits = floatBitsToUint(v);
    uint dropped = bits & ((1u << HDR_DROPPED_BITS) - 1u);
    return (bits >> HDR_DROPPED_BITS) | (dropped != 0u ? 1u : 0u);
}
SSGI_INLINE float hdrValue(uint bits21) {
    return uintBitsToFloat(bits21 << HDR_DROPPED_BITS);
}

// CacheConstants.refreshTileCorner packs a pixel's x and y into one int (screens are narrower).
#define REFRESH_TILE_ROW 65536

// The temporal cache of one effect (thesis 3.1; docs/temporal-cache.md), as its passes see it
// each frame. Push constants (std430) pack these scalars as C++ does.
struct CacheConstants {
    int historyValid;      // 1 when last frame's history may be read
    int rotations;         // rotations until a pixel is converged
    int refreshTileCorner; // this frame's refresh tile's top-left pixel, x + REFRESH_TILE_ROW * y
                           // (TileRefresh::rect places it), or -1: none
    int tileSize;          // the refresh tile's side, pixels
    float confidenceBias;  // bias of the thesis's confidence rule (eq. 4)
    int runningMean;       // 1 for the running mean, 0 for the thesis's rule
    int motionTest;        // MOTION_*: what a moved object (FrameUniforms.motion) restarts
    float motionReach;     // scene units
    float blurBudget;      // the resampling blur (squared pixels) a cached value may carry:
                           // beyond it the history's weight is cut and the pixel recomputed
    int reprojection;      // REPROJECT_* and REUSE_* flags (temporal.glsl)
};
SSGI_CHECK_SIZE(CacheConstants, 40);

// The reprojection pass's settings (reproject.comp), from the cache's (CacheConstants).
struct ReprojectionConstants {
    float epsilon;    // the reprojection test, in pixel footprints (cache_epsilon)
    int thinGeometry; // 1: where the nearest texel fails, try the texels beside it
    int historyValid; // 0: last frame's view depths hold nothing (every pixel: not found)
};
SSGI_CHECK_SIZE(ReprojectionConstants, 12);

// Per-frame values of the screen-space passes (push constants). Structural settings (tap and
// sample counts, variants) are specialization constants instead. `rotation` turns the
// sampling pattern each frame and `scale` varies its size, so that successive frames take
// different samples (thesis 3.1.2).
struct ShadowConstants {
    float rotation;     // the pattern's turn this frame (radians)
    float scale;        // its size's jitter
    float normalOffset; // the receiver's offset along its normal (shadow-map texels)
    float radialOffset; // common.glsl radialOffset
    CacheConstants cache;
};
SSGI_CHECK_SIZE(ShadowConstants, 56);

struct AoConstants {
    float rotation, scale, radius, radialOffset; // radius: the AO radius (scene units)
    float falloffA, falloffB;                    // D(d) = 1 + a d + b d^2 (d in AO radii)
    float unused[2];
    CacheConstants cache;
};
SSGI_CHECK_SIZE(AoConstants, 72);

// Interleaved sampling of the VPLs (Keller and Heidrich 2001): the pattern's VPLs 0..n-1 are
// split into k*k disjoint subsets, subset s holding VPLs s, s + k*k, s + 2*k*k, ...; a pixel
// gathers the subset its place in a k x k block names, so every block of k x k pixels gathers
// each VPL exactly once (tests/test_effects.cpp checks it).
SSGI_INLINE int vplSubset(int x, int y, int k) {
    return (y % k) * k + (x % k);
}
// The j-th VPL of subset s, and how many VPLs of n the subset holds.
SSGI_INLINE int vplOfSubset(int s, int j, int k) {
    return s + j * k * k;
}
SSGI_INLINE int vplSubsetSize(int s, int n, int k) {
    return s < n ? (n - s + k * k - 1) / (k * k) : 0;
}

// Where a pixel's VPLs lie in the reflective shadow map: a polar pattern around the pixel's
// projection c, whose density falls as 1/r with the distance r from c (the thesis's r = R xi1,
// 3.3), so that the close VPLs, whose 1/d^2 dominates at creases and contacts, are drawn most.
// - With a sampling radius R > 0 (the RSM paper's r_max): the disk of radius R, density
//   1 / (2 pi R r); points that fall outside the map are lost.
// - With R = 0 (the whole map): the same 1/r density over the map alone, nothing lost. The
//   direction is drawn in proportion to how far the map reaches along it, and r uniformly up to
//   the map's edge: density 1 / (Z r), Z the integral of that reach over the angle. Along an
//   edge at distance d from c the reach is d / cos(psi), whose integral over psi is
//   d asinh(tan psi), so each edge's share of Z and the point where a direction leaves the map
//   are closed forms.
// A sample (xi1, xi2) in [0, 1)^2 maps to r = xi1 x reach, its direction xi2 of the way round;
// of n samples, each stands for the map's area 1 / (n density) = Z r / n (tests/test_effects.cpp
// checks that they add up to the map's area and integrate functions over it).
struct VplPattern {
    vec2 center;
    float radius; // > 0: the disk's; 0: the whole map
    float total;  // Z: 1 / (total r) is the density per unit of the map's uv area
    // The whole-map pattern's edges, counter-clockwise (right, top, left, bottom): each seen
    // from c as the map's right edge turned by e quarter turns, at distance d (at least 1e-4),
    // running from lo to lo + 1 (0 at the foot of the perpendicular from c). `start`:
    // asinh(lo / d), where its directions begin; `before`: the shares of the edges before it.
    vec4 d, lo, start, before;
};

// `center` in [0, 1]^2; an edge closer to it than 1e-4 subtends no angle and gets no share.
SSGI_INLINE VplPattern vplPattern(vec2 center, float radius) {
    VplPattern pattern;
    pattern.center = center;
    pattern.radius = radius;
    pattern.total = 6.28318531f * radius; // the disk's: 2 pi R
    pattern.d = max(vec4(1.0f - center.x, 1.0f - center.y, center.x, center.y), vec4(1e-4f));
    pattern.lo = vec4(-center.y, center.x - 1.0f, center.y - 1.0f, -center.x);
    pattern.start = vec4(0.0f);
    pattern.before = vec4(0.0f);
    if (radius > 0.0f) return pattern;
    float sum = 0.0f;
    for (int e = 0; e < 4; ++e) {
        float d = pattern.d[e];
        pattern.start[e] = asinh(pattern.lo[e] / d);
        pattern.before[e] = sum;
        // The reach along the edge's directions, d / cos(psi), integrates to d asinh(tan psi).
        if (d > 1e-4f) sum += d * (asinh((pattern.lo[e] + 1.0f) / d) - pattern.start[e]);
    }
    pattern.total = sum;
    return pattern;
}

// The point of VPL i of n in the map's uv (outside [0, 1)^2 only for a disk), and its distance
// r from the centre: a Fibonacci lattice, xi1 = (i + stratum) / n (stratum in [0, 1): where in
// its ring) and xi2 = i / golden ratio^2 + rotation / 2 pi (the golden angle's turns).
SSGI_INLINE vec2 vplPatternPoint(VplPattern pattern, int i, int n, float stratum, float rotation,
                                 SSGI_OUT(float) r) {
    float xi1 = (float(i) + stratum) / float(n);
    float turns = float(i) * 0.381966011f + rotation / 6.28318531f;
    float xi2 = turns - floor(turns);
    if (pattern.radius > 0.0f) {
        float theta = 6.28318531f * xi2;
        r = pattern.radius * xi1;
        return pattern.center + r * vec2(cos(theta), sin(theta));
    }
    // The edge whose share holds xi2 (one without a share is passed over), then the offset along
    // it where asinh(offset / d) - start = (the rest of xi2's part) / d.
    float m = xi2 * pattern.total;
    int e = int(m >= pattern.before.y) + int(m >= pattern.before.z) + int(m >= pattern.before.w);
    float d = pattern.d[e];
    float x = exp(pattern.start[e] + (m - pattern.before[e]) / d);
    float offset = clamp(0.5f * d * (x - 1.0f / x), pattern.lo[e], pattern.lo[e] + 1.0f);
    vec2 toExit = vec2(d, offset); // on the right edge; turned by e quarter turns
    if ((e & 1) != 0) toExit = vec2(-toExit.y, toExit.x);
    if ((e & 2) != 0) toExit = -toExit;
    r = xi1 * length(toExit);
    return pattern.center + xi1 * toExit;
}

// The pattern's density per unit of uv area at distance r from the centre (r at least half a
// texel of a map `size` texels wide, where 1/r would spike).
SSGI_INLINE float vplPatternDensity(VplPattern pattern, float r, float size) {
    if (pattern.radius > 0.0f && r > pattern.radius) return 0.0f;
    return 1.0f / (pattern.total * max(r, 0.5f / size));
}

struct IndirectConstants {
    float rotation;     // the pattern's turn this frame (radians)
    float scale;        // its size's jitter (with a sampling radius > 0)
    float radius;       // the sampling radius, a fraction of the RSM (0: the whole map)
    float radialOffset; // common.glsl radialOffset
    int width, height;  // the gather's image (method 0: the half-resolution one)
    int axisX, axisY;   // the interleaved method's filter: the axis of this pass
    CacheConstants cache;
    float visibilityStart; // indirect_visibility_start (indirect_visibility.glsl)
};
SSGI_CHECK_SIZE(IndirectConstants, 76);

// The VPLs of indirect_method 2 (indirect_vpls.comp): the RSM clustered into a coarser VPL
// map, and a pyramid of the VPLs' flux luminance (level 0 the map padded to `paddedSize`, a
// power of two; level `levels` the total) through which VPLs are drawn in proportion to it.
struct VplDrawConstants {
    int cached;     // 1: the draw's points move frame by frame; 0: every frame draws the same
    int mapSize;    // the RSM's side, texels
    int vplMapSize; // the VPL map's side: mapSize / indirect_vpl_cluster, rounded up
    int paddedSize; // the pyramid's level 0 side: a power of two, at least vplMapSize and 8
    int levels;     // log2(paddedSize)
    int unused[3];
};
SSGI_CHECK_SIZE(VplDrawConstants, 32);

struct SsdoConstants {
    float rotation, scale;
    float rMax;           // r_max (scene units)
    float bounceStrength; // the screen-space bounce's weight
    CacheConstants cache;
};
SSGI_CHECK_SIZE(SsdoConstants, 56);

struct ContactConstants {
    float segmentTexels; // the march's length in shadow-map texels at the pixel
    float unused[3];
};
SSGI_CHECK_SIZE(ContactConstants, 16);

// The temporal pass (temporal.comp) carries up to this many cached effects a dispatch, one a slot;
// its storage buffer (std430, laid out as C++ lays it out) holds each slot's cache this frame.
#define TEMPORAL_EFFECT_SLOTS 4
struct TemporalEffects {
    CacheConstants effects[TEMPORAL_EFFECT_SLOTS];
};
SSGI_CHECK_SIZE(TemporalEffects, 160);

// Sky visibility maps (sky_maps.glsl): orthographic depth maps of the scene from `tile.y`
// directions over the sphere, tiled `tile.z` to a row of an atlas, `tile.w` texels a side each,
// around the scene's bounding sphere (`sphere`: centre, radius). The raster pass draws map
// `tile.x` (one uniform buffer per map); the lookup reads them all.
struct SkyMapView {
    vec4 sphere;
    ivec4 tile;
};
SSGI_CHECK_SIZE(SkyMapView, 32);

// The sky visibility lookup (push constants): the maps as above, the distance below which an
// occluder is left to the screen-space AO (its radius; 0 without AO) and the receiver's offset
// along its normal, in scene units.
struct SkyVisibilityConstants {
    SkyMapView maps;
    float aoReach;
    float normalOffset;
    float unused[2];
    CacheConstants cache;
};
SSGI_CHECK_SIZE(SkyVisibilityConstants, 88);

// The sky's occluders the lookup tests exactly instead of through the maps: the triangles of
// the scene's single quads and triangles (floors, walls), corners 3i..3i+2 in the GPU's
// coordinates (a uniform buffer; sky_visibility_pass.cpp).
#define SKY_TRIANGLES_MAX 32
struct SkyTriangles {
    ivec4 count; // x: how many
    vec4 corners[3 * SKY_TRIANGLES_MAX];
};
SSGI_CHECK_SIZE(SkyTriangles, 16 + 3 * 32 * 16);

// The world cache of indirect_method 3 (world_cache_pass.cpp): a hash table of cells in world
// space (world_cache.glsl), each the bounce gathered at one surface point from the flux's VPLs
// with the visibility of a voxel occupancy grid (world_voxels.glsl), which pixels look up.
struct WorldConstants {
    // x: the angle a cell spans from the camera (world_cell_angle, radians); y: 1 where a pixel
    // may take the cell one level coarser or finer (world_level_reuse); z: frames
    // of samples a cell accumulates (world_frames); w: frames of samples a new cell gathers at
    // once (world_new_cell_frames)
    vec4 cells;
    ivec4 table; // x: the table images' width; y: entries; z: frames unused before eviction; w: unused
    // x: VPLs a cell gathers a frame; y: cells refreshed a frame beyond the new ones; z: the
    // flux pool's size; w: what the lookup writes (WORLD_VIEW_*)
    ivec4 work;
    // x: unused; y: 1 on a frame the light moved (every cell restarts); z: 1 on a frame an
    // object moved; w: the VPL map's side
    vec4 change;
};
SSGI_CHECK_SIZE(WorldConstants, 64);
#define WORLD_BLOCK 4 // voxels a side of the voxel grid's blocks (world_voxels.glsl)
#define WORLD_DISTANCE_CAP 8u // the farthest distance, in blocks, world.voxel_distance holds
#define WORLD_VIEW_LIGHT 0 // the bounce, interpolated between cells
#define WORLD_VIEW_CELLS 1 // each pixel's own cell's value, its edges unblended
#define WORLD_VIEW_AGE 2   // each pixel's own cell: green its samples' share of world_frames,
                           // red where it holds none, blue its frames since last used
// The world cache's counters (world.stats, R32UI, a row per frame parity, and row 2 held from
// frame to frame): what `render --profile` prints.
#define WORLD_STAT_LIVE 0      // cells in the table after eviction
#define WORLD_STAT_NEW 1       // cells filled for the first time (or restarted) this frame
#define WORLD_STAT_REFRESHED 2 // cells that gathered more samples this frame
#define WORLD_STAT_EVICTED 3   // cells evicted this frame
#define WORLD_STAT_FULL 4      // pixels whose cell found no free entry within its probes
#define WORLD_STAT_SHORT 5     // cells short of world_frames frames of samples, not new: the
                               // refresh's candidates; row 2: their number the last frame that
                               // gathered (world_schedule.comp's refresh window)
#define WORLD_STAT_LISTED 6    // cells listed for world.gather (new and refreshed)
// world.gather's workgroups, x, y and z (a VkDispatchIndirectCommand, copied to a buffer): a
// workgroup per 64 listed cells, at most WORLD_GATHER_GROUPS_X along x (the least limit Vulkan
// allows is 65,535), the rows along y.
#define WORLD_STAT_GROUPS 7
#define WORLD_GATHER_GROUPS_X 32768u
// world_half_res: pixels world.upsample listed for world.lookup_edges (those with no half-res
// sample on their surface, or every pixel in a debug view), and that pass's workgroups, x, y, z.
#define WORLD_STAT_EDGES 10
#define WORLD_STAT_EDGE_GROUPS 11
// world.gather's samples left out where a loop limit stopped a lane's walks (lavapipe stops an
// invocation's loops after 65,535 iterations in all; world_gather.comp)
#define WORLD_STAT_CUT 14
#define WORLD_STATS 15

// How a lighting term enters the composite's sum (composite.comp). The pass that makes a term
// registers it by its view's name (FrameBuild::addCompositeTerm); the view table
// (renderer/passes/views.h) gives each term's view its role.
#define TERM_NONE 0           // an unused slot
#define TERM_SKY_OCCLUSION 1  // r: the fraction of the sky's light let through (the AO)
#define TERM_SKY_FILTER 2     // rgb: the same, per colour (the sky's visibility beyond the AO)
#define TERM_SKY_RADIANCE 3   // rgb: radiance that replaces the sky light (SSDO)
#define TERM_IRRADIANCE 4     // rgb: irradiance / pi, times the albedo, added (the bounce)
#define COMPOSITE_TERMS 4     // the term slots composite.comp binds (term0..term3)

// Composite's choice of output (push constants), and where the output lies in the screen
// images it reads: `guardBand` pixels in from their top left corner (the guard_band setting).
// For a term's view (VIEW_TERM): the slot holding it (-1 when the frame has no such term) and
// its role (TERM_*).
struct CompositeConstants {
    int view; // VIEW_*
    int guardBand;
    int termSlot;
    int termRole;
};
SSGI_CHECK_SIZE(CompositeConstants, 16);

// The composite's own views; every lighting term's view is VIEW_TERM.
#define VIEW_FINAL 0
#define VIEW_ALBEDO 1
#define VIEW_NORMAL 2
#define VIEW_DEPTH 3
#define VIEW_DIRECT 4
#define VIEW_RSM_FLUX 5
#define VIEW_RSM_NORMAL 6
#define VIEW_SHADOW 7
#define VIEW_CONTACT 8
#define VIEW_PEEL 9
#define VIEW_TERM 10

#ifdef __cplusplus
} // namespace ssgi::shader
#endif
#endif
