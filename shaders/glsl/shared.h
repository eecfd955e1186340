// Structures shared by C++ and GLSL: one declaration, compiled by both. Members are only vec4,
// mat4 and ivec4 so that std140 (uniforms) and std430 (push constants) lay them out exactly as
// C++ does; the static_asserts hold the C++ side to the sizes the shaders expect.
#ifndef SSGI_SHARED_H
#define SSGI_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace ssgi::shader {
using vec4 = glm::vec4;
using mat4 = glm::mat4;
using ivec4 = glm::ivec4;
#define SSGI_CHECK_SIZE(type, bytes) static_assert(sizeof(type) == bytes, #type " layout")
#define SSGI_INLINE inline
#else
#define SSGI_CHECK_SIZE(type, bytes)
#define SSGI_INLINE
#endif

// Everything a pass may need about the frame: cameras, the light, the sky. Set 0, binding 0.
struct FrameUniforms {
    mat4 view;
    mat4 projection;
    mat4 viewProjection;
    mat4 inverseViewProjection;
    mat4 previousViewProjection;
    mat4 lightViewProjection;
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
    vec4 params;         // x = exposure, y = shadow bias (texels), z = frame index, w = scene diagonal
    // Objects that moved since the last frame: box i spans movedBoxes[2i].xyz..movedBoxes[2i+1].xyz
    // (world space, old and new place together); motion.x = number of boxes (at most 4).
    vec4 movedBoxes[8];
    vec4 motion;
    // x = the power of two every light, sky and so every radiance in the intermediate images is
    // divided by, so that a very bright scene fits their half floats (65504 at most); 1 for the
    // usual scene. The composite multiplies it back.
    vec4 radianceScale;
};
SSGI_CHECK_SIZE(FrameUniforms, 7 * 64 + 20 * 16);

// Per draw in the raster passes (push constants).
struct DrawConstants {
    mat4 model;
    vec4 baseColorFactor;
    vec4 material; // x = 1 when a base-colour texture is bound, y = alpha cutoff (0 = opaque)
};
SSGI_CHECK_SIZE(DrawConstants, 96);

// The temporal cache of one effect (thesis 3.1; docs/temporal-cache.md), as its passes see it each frame.
struct CacheConstants {
    ivec4 state; // x = 1 when last frame's history may be read, y = rotations until a pixel is
                 // converged, z = this frame's refresh tile (-1 = none), w = tile size (pixels)
    vec4 accumulation; // x = bias of the confidence rule (eq. 4), y = reprojection epsilon in
                       // pixel footprints (eq. 3), z = 1 for the running mean, w = 1 when the
                       // whole screen is converged and passes run over the refresh tile alone
    vec4 invalidation; // what a moved object (FrameUniforms.motion) restarts: x = 0 nothing
                       // here (the renderer resets the whole history), 1 pixels within y of a
                       // moved box, 2 pixels whose path to the light passes within y of one;
                       // z = the resampling blur a cached value may carry (squared pixels):
                       // beyond it the history's weight is cut and the pixel recomputed
};
SSGI_CHECK_SIZE(CacheConstants, 48);

// Per-frame values of the screen-space passes (push constants). Structural settings (tap and
// sample counts, variants) are specialization constants instead. `rotation` turns the
// sampling pattern each frame and `scale` varies its size, so that successive frames take
// different samples (thesis 3.1.2).
struct ShadowConstants {
    vec4 pattern; // x = rotation (radians), y = scale, z = normal offset (texels), w = radial
                  // offset (common.glsl radialOffset)
    CacheConstants cache;
};
SSGI_CHECK_SIZE(ShadowConstants, 64);

struct AoConstants {
    vec4 pattern; // x = rotation, y = scale, z = AO radius (scene units), w = radial offset
    vec4 falloff; // x = a, y = b of D(d) = 1 + a d + b d^2 (d in AO radii)
    CacheConstants cache;
};
SSGI_CHECK_SIZE(AoConstants, 80);

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

struct IndirectConstants {
    vec4 pattern; // x = rotation, y = scale, z = sampling radius (fraction of the RSM), w = radial
                  // offset
    ivec4 target; // xy = size of the half-resolution image
    CacheConstants cache;
};
SSGI_CHECK_SIZE(IndirectConstants, 80);

struct SsdoConstants {
    vec4 pattern; // x = rotation, y = scale, z = r_max (scene units), w = bounce strength
    CacheConstants cache;
};
SSGI_CHECK_SIZE(SsdoConstants, 64);

struct ContactConstants {
    vec4 params; // x = segment length in shadow-map texels at the pixel
};
SSGI_CHECK_SIZE(ContactConstants, 16);

// The temporal pass of one effect: its cache state (push constants).
struct TemporalConstants {
    CacheConstants cache;
};
SSGI_CHECK_SIZE(TemporalConstants, 48);

// Sky visibility maps (sky_maps.glsl): orthographic depth maps of the scene from `tile.y`
// directions over the sphere, tiled `tile.z` to a row of an atlas, `tile.w` texels a side each,
// around the scene's bounding sphere (`sphere`: centre, radius). The raster pass draws map
// `tile.x` (one uniform buffer per map); the lookup reads them all.
struct SkyMapView {
    vec4 sphere;
    ivec4 tile;
};
SSGI_CHECK_SIZE(SkyMapView, 32);

// The sky visibility lookup (push constants): the maps as above, and `params`: x = the distance
// below which an occluder is left to the screen-space AO (its radius; 0 without AO), y = the
// receiver's offset along its normal, in scene units.
struct SkyVisibilityConstants {
    SkyMapView maps;
    vec4 params;
};
SSGI_CHECK_SIZE(SkyVisibilityConstants, 48);

// Composite's choice of output (push constants): x = view (see VIEW_*).
struct CompositeConstants {
    ivec4 mode;
};
SSGI_CHECK_SIZE(CompositeConstants, 16);

#define VIEW_FINAL 0
#define VIEW_ALBEDO 1
#define VIEW_NORMAL 2
#define VIEW_DEPTH 3
#define VIEW_DIRECT 4
#define VIEW_RSM_FLUX 5
#define VIEW_RSM_NORMAL 6
#define VIEW_SHADOW 7
#define VIEW_AO 8
#define VIEW_INDIRECT 9
#define VIEW_SSDO 10
#define VIEW_CONTACT 11
#define VIEW_PEEL 12
#define VIEW_SKY_VISIBILITY 13

#ifdef __cplusplus
} // namespace ssgi::shader
#endif
#endif
