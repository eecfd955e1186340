// The frame's passes, each added to the graph by one function in its own file (ao_pass.cpp,
// shadow_pass.cpp, ...), and the whole frame in order (frame.cpp). Every pass reads what it is
// handed and the FrameBuild (frame_build.h); what changes from frame to frame reaches it as the
// FrameState the graph hands its callbacks (frame_state.h).
#pragma once

#include "cache/cache.h"
#include "graph/frame_graph.h"
#include "passes/cached_effect_pass.h"
#include "passes/frame_build.h"
#include "passes/scene_pass.h"
#include "shared.h"

#include <optional>

namespace ssgi {

// The cached effects of one pass (cached_effect_pass.h) return what their consumers read: the
// blended history, or the raw value without a cache. A lighting term's pass also hands it to the
// composite (FrameBuild::addCompositeTerm), under its view's name: "ao", "ssdo", "indirect",
// "sky-visibility".
// reprojection: where each pixel's surface lay last frame, for every cached effect; computed when
// caching is on, before the first cached effect; its image is CacheSet::reprojection, which
// cacheBindings hands every cached effect's passes (a one-texel stand-in without the cache).
void addReprojectionPass(FrameBuild& build, const GBuffer& gbuffer);
// shadow: fraction of the spot light's disk each pixel sees (PCF/PCSS, or a hard test).
graph::ImageRef addShadowPass(FrameBuild& build, const GBufferAndRsm& inputs);
// contact: the shadow term with screen-space contact shadows added; with depth peeling's second
// layer (inputs.secondLayer), an occluder is a sample between the two layers.
graph::ImageRef addContactPass(FrameBuild& build, const GBufferAndRsm& inputs,
                               graph::ImageRef shadow);
// light_depth_min: the light's nearest depth in blocks of the RSM's texels, for the bounce's
// visibility test's light check (light_depth_min_pass.cpp).
graph::ImageRef addLightDepthMinPass(FrameBuild& build, const Rsm& rsm);
// The binding "lightDepthMin" of the bounce's gathers: inputs.lightDepthMin, or without the
// light check the RSM's depth, an image the shaders (LIGHT_CHECK 0) never read.
ShaderImage lightDepthMinInput(const GBufferAndRsm& inputs);
// peel: the second depth layer (world position of the next surface behind the G-buffer's).
graph::ImageRef addPeelPass(FrameBuild& build, const GBufferAndRsm& inputs);
// The binding "secondLayer" of a pass whose occlusion test may use two layers (SSDO, contact
// shadows, the bounce's visibility test, the composite's view): inputs.secondLayer, or without
// depth peeling the view depth, an image the shader (PEELING 0) never reads.
ShaderImage secondLayerInput(const GBufferAndRsm& inputs);
// direct: spot-light radiance times the shadow term.
graph::ImageRef addDirectPass(FrameBuild& build, const GBufferAndRsm& inputs,
                              graph::ImageRef shadow);

// ao: visibility of the hemisphere within the AO radius (1 = open).
graph::ImageRef addAoPass(FrameBuild& build, const GBufferAndRsm& inputs);

// The push constants of the indirect light's passes this frame (every method's gather, the
// upsampling, the filter's axes; the filter's axis left 0): the pattern's turn, scale and
// radial place, the sampling radius and the visibility march's start, the cache's state;
// `gather` is the size of the image the gather writes.
shader::IndirectConstants indirectConstants(const FrameBuild& build, const EffectCache* cache,
                                            const FrameState& frame, VkExtent2D gather);

// indirect (half resolution) + upsample, indirect_method 0: one-bounce irradiance / pi from
// the RSM's VPLs.
graph::ImageRef addIndirectPasses(FrameBuild& build, const GBufferAndRsm& inputs,
                                  const EffectCache* cache);

// indirect.flux + indirect.vpls, indirect_methods 2 and 3: the RSM clustered into a coarser map
// of VPLs, and the list of VPLs drawn this frame in proportion to their flux (a new draw each
// frame when `moving`, else the same every frame).
struct FluxVpls {
    graph::ImageRef position, normal, flux, list;
};
FluxVpls addFluxVplPasses(FrameBuild& build, const GBufferAndRsm& inputs, bool moving);

// A transfer pass `name` that clears `images` to zero on the frames `enabled` names
// (clear_pass.cpp).
void addClearPass(FrameBuild& build, const std::string& name,
                  const std::vector<graph::ImageRef>& images, graph::EnabledFn enabled);

// world.voxel_clear + world.voxelize, indirect_method 3: the scene's voxel occupancy grid, drawn
// where the frame places it (FrameUniforms.worldGridOrigin, worldGridSize; world_grid.h) on
// the frames FrameState::drawVoxels names (world_voxels_pass.cpp).
struct WorldGrid {
    graph::ImageRef voxels, distance; // world_voxels.glsl
};
WorldGrid addWorldVoxelPasses(FrameBuild& build);

// The world cache's table holds 2^this cells: world_table_bits, or where it is 0, from the
// image's size (world_cache_pass.cpp).
int worldTableBits(const Settings& settings, VkExtent2D size);
// world.clear + world.insert + world.schedule + world.gather + world.lookup, indirect_method 3:
// the bounce from cells of a hash table in world space, which gather the flux's VPLs
// (`vpls.list`) with their visibility in `grid`; with `sky` (skyInWorldCache), the cells hold
// the sky's visibility in those maps too. Returns both looked up at every pixel
// (world_cache_pass.cpp); `skyVisibility` is invalid without `sky`.
struct SkyMaps;
struct WorldLookups {
    graph::ImageRef indirect, skyVisibility;
};
WorldLookups addWorldCachePasses(FrameBuild& build, const GBufferAndRsm& inputs,
                                 const FluxVpls& vpls, const WorldGrid& grid, const SkyMaps* sky);

// indirect (interleaved VPL subsets) + indirect.filter_x + indirect.filter_y: the same light,
// indirect_method 1; with `fluxVpls` (method 2) the flux's VPLs beside the pattern's.
graph::ImageRef addInterleavedIndirectPasses(FrameBuild& build, const GBufferAndRsm& inputs,
                                             const EffectCache* cache,
                                             const FluxVpls* fluxVpls = nullptr);

// The one-bounce indirect light, cached, by the method the settings choose (indirect_light.cpp);
// with `sky` (skyInWorldCache), the world cache's sky's visibility as a term too.
graph::ImageRef addIndirectLight(FrameBuild& build, const GBufferAndRsm& inputs,
                                 const SkyMaps* sky);

// ssdo: directionally occluded sky light plus one bounce, as radiance. Depth peeling's second
// layer (inputs.secondLayer) makes its occlusion test two-layered.
graph::ImageRef addSsdoPass(FrameBuild& build, const GBufferAndRsm& inputs, graph::ImageRef direct);

// What the composite reads beside the lighting terms the passes hand it
// (FrameBuild::compositeTerms) and its inputs (depth peeling's second layer for its view): the
// direct light and the shadow term for its views.
struct CompositeImages {
    graph::ImageRef direct, shadow;
};

// sky.maps: depth maps of the scene over the sky's directions, in one atlas, and what a lookup
// of the sky's visibility in them needs (sky_visibility.glsl; sky_visibility_pass.cpp).
struct SkyMaps {
    graph::ImageRef atlas;
    vk::Buffer exactTriangles; // TrianglesBlock: the occluders tested exactly
    shader::SkyMapView view;
    float aoReach = 0.0f;      // occluders nearer are the AO's
    float normalOffset = 0.0f; // a receiver's offset along its normal
};
SkyMaps addSkyMapsPass(FrameBuild& build);
// sky_visibility: the fraction of the sky's light reaching each pixel past the occluders beyond
// the AO's radius, looked up in `maps`, cached; not made where the world cache's cells hold it
// (skyInWorldCache).
graph::ImageRef addSkyVisibilityPass(FrameBuild& build, const GBufferAndRsm& inputs,
                                     const SkyMaps& maps);

struct CompositeOutputs {
    graph::ImageRef hdr, ldr;
};
// composite: HDR radiance (the direct light plus the lighting terms, each by its role),
// tonemapped sRGB image, or the debug view FrameState::view names, at the output's size (the
// screen images less their guard band).
CompositeOutputs addCompositePass(FrameBuild& build, const GBufferAndRsm& inputs,
                                  const CompositeImages& images);

// The whole frame, every pass above in order, as the scene's settings ask (frame.cpp).
void addFramePasses(FrameBuild& build);

} // namespace ssgi
