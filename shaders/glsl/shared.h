// Structures shared by C++ and GLSL: one declaration, compiled by both. The uniform block's
// members are only vec4, mat4 and ivec4, so that std140 lays them out exactly as C++ does; push
// constants (std430) may also hold int and float scalars. The static_asserts hold the C++ side
// to the sizes the shaders expect. Here: the frame's uniforms, a draw's constants, the display
// transform and the HDR output's encoding, the screen-space effects', the sky maps', the world
// cache's and the composite's; the temporal cache's (shared_cache.h) and the VPLs'
// (shared_vpls.h) in their own headers, which this one includes, and the C++ side's GLSL types
// in shared_language.h. Shaders and C++ include this one.
#ifndef SSGI_SHARED_H
#define SSGI_SHARED_H

#include "shared_cache.h"
#include "shared_language.h"
#include "shared_vpls.h"

#ifdef __cplusplus
namespace ssgi::shader {
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

// The sky's visibility the world cache's cells hold (world_sky_visibility.comp, a uniform
// buffer; indirect_method 3 with world_sky_visibility): the maps, and in `reach` the two
// distances of SkyVisibilityConstants, x aoReach and y normalOffset.
struct WorldSky {
    SkyMapView maps;
    vec4 reach;
};
SSGI_CHECK_SIZE(WorldSky, 48);

// The world cache of indirect_method 3 (world_cache_pass.cpp): a hash table of cells in world
// space (world_cache.glsl), each the bounce gathered at one surface point from the flux's VPLs
// with the visibility of a voxel occupancy grid (world_voxels.glsl), which pixels look up.
struct WorldConstants {
    // x: the angle a cell spans from the camera (world_cell_angle, radians); y: 1 where a pixel
    // may take the cell one level coarser or finer (world_level_reuse); z: frames
    // of samples a cell accumulates (world_frames); w: frames of samples a new cell gathers at
    // once (world_new_cell_frames)
    vec4 cells;
    // x: the table images' width; y: entries; z: frames unused before eviction; w: unused
    ivec4 table;
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
// The world cache's counters (world.stats, R32UI, a row per frame parity): what `render
// --profile` prints. Row 2 holds, from frame to frame, what world.schedule needs of the frame
// before (world_insert.comp keeps it): at WORLD_STAT_LIVE its live cells, at WORLD_STAT_SHORT
// its short and new cells, at WORLD_STAT_WINDOW the refresh window's start.
#define WORLD_STAT_LIVE 0      // cells in the table after eviction
#define WORLD_STAT_NEW 1       // cells filled for the first time (or restarted) this frame
#define WORLD_STAT_REFRESHED 2 // cells that gathered more samples this frame
#define WORLD_STAT_EVICTED 3   // cells evicted this frame
#define WORLD_STAT_FULL 4      // pixels whose cell found no free entry within its probes
#define WORLD_STAT_SHORT 5     // cells short of world_frames frames of samples, not new: the
                               // refresh's candidates
#define WORLD_STAT_WINDOW 2    // (row 2 only) the refresh window's start, 24-bit fixed point
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
