// What every pass needs to set itself up: the device, the graph to add itself to, the scene on
// the device, the frame's uniforms and samplers, and the frame's sizes. Owned by the Renderer,
// so the passes' record functions may keep a pointer to it.
#pragma once

#include "cache/cache.h"
#include "graph/frame_graph.h"
#include "passes/compute_pass.h"
#include "scene_gpu.h"
#include "shared.h"
#include "vk/pipeline.h"

#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace ssgi {

struct PassSetup {
    vk::Context& ctx;
    graph::FrameGraph& graph;
    const SceneGpu& scene;
    const Scene& model; // settings, light, bounds
    vk::Buffer frameUniforms;
    VkSampler nearestSampler = VK_NULL_HANDLE;
    VkSampler linearSampler = VK_NULL_HANDLE;
    VkExtent2D size{};                   // every screen image: the output and the guard band
    uint32_t guardBand = 0;              // pixels beyond each edge of the output (guard_band)
    glm::dvec3 gpuOrigin{0.0};           // the world point at the GPU's origin (renderer.cpp)
    VkExtent2D rsmSize{};                // the reflective shadow map
    std::vector<vk::Pipeline> pipelines; // destroyed with the renderer
    std::map<std::string, size_t> computePipelines; // computePipeline()'s, by what makes them
    std::vector<vk::Buffer> buffers;                // likewise (the sky maps' views)
    // This frame's turn and scale of every sampling pattern (thesis 3.1.2); set by the renderer.
    float patternRotation = 0.0f;
    float patternScale = 1.0f;
    // Where in their radial strata a cached effect's samples lie this frame, in [0, 1): frame
    // by frame the accumulation fills the radii between one frame's samples (AO steps, VPL
    // rings, PCF rings) as the turn fills the angles.
    float patternOffset = 0.5f;
    std::deque<EffectCache> caches; // empty when caching is off
    // With caching on, the G-buffer's view depths (its world positions, gbuffer_position.glsl)
    // are a history pair: last frame's is what every cached effect reprojects against (each
    // keeps only its own value and count).
    std::optional<uint32_t> viewDepthHistory;
    // With the cache on, the RSM is drawn again only when the light changes.
    bool rsmStale = true;
    // The sky visibility maps are drawn again only when an object moved.
    bool skyMapsStale = true;
    // The camera is where it was last frame, and nothing moved.
    bool cameraStill = false;
    // Camera and light unchanged for as many frames as a pixel needs rotations: every pixel is
    // converged, and the cached effects run over their refresh tiles alone.
    bool settled = false;
    // What the composite shows (a VIEW_* value); the renderer may change it between frames.
    int view = 0;

    // A compute pipeline for `desc` (compute_pass.cpp), made once and shared by every pass that
    // asks for the same shader, layout and specialization (the interleaved filter's two axes).
    const vk::Pipeline& computePipeline(const ComputePassDesc& desc,
                                        const std::vector<vk::LayoutBinding>& layout);
    // Where the output ("hdr", "ldr") lies in the screen images: the guard band in from each edge.
    VkRect2D output() const {
        return {{int32_t(guardBand), int32_t(guardBand)},
                {size.width - 2 * guardBand, size.height - 2 * guardBand}};
    }
};

// The G-buffer (camera view) and the reflective shadow map (light view) are the same kind of
// pass: colour targets and a depth target, the whole scene drawn once. Neither keeps world
// positions: the G-buffer's follow from its view depth (R32F; gbuffer_position.glsl), the RSM's
// from the distance along the light's axis in its VPL texels (rsm_vpl.glsl).
struct SceneTarget {
    const char* suffix; // the image is the pass's name + suffix
    VkFormat format;
};
struct SceneTargets {
    std::vector<graph::ImageRef> colors; // in the fragment shader's order
    graph::ImageRef depth;
};
// `enabled` (optional) is asked each frame whether to draw; the targets of a pass that may be
// skipped persist from frame to frame. With `firstTargetHistory`, the first colour target is a
// history pair (colors[0] is its current side), whose id is written there.
SceneTargets addScenePass(PassSetup& setup, const std::string& name, const std::string& shader,
                          VkExtent2D extent, const std::vector<SceneTarget>& targets,
                          std::function<bool()> enabled = {},
                          std::optional<uint32_t>* firstTargetHistory = nullptr);

// gbuffer: view depth (0 where nothing was drawn), normal, albedo, depth.
struct GBuffer {
    graph::ImageRef viewDepth, normal, albedo, depth;
};
GBuffer addGBufferPass(PassSetup& setup);
// rsm: one VPL a texel (RGBA32UI: albedo, the light's share, normal, distance along the light's
// axis; rsm_vpl.glsl) and the depth target (the shadow map). Drawn only while `setup.rsmStale`
// says the light moved since it was last drawn (or there is no cache).
struct Rsm {
    graph::ImageRef vpls, depth;
};
Rsm addRsmPass(PassSetup& setup);

struct GBufferAndRsm {
    GBuffer gbuffer;
    Rsm rsm;
};
// shadow: fraction of the spot light's disk each pixel sees (PCF/PCSS, or a hard test).
graph::ImageRef addShadowPass(PassSetup& setup, const GBufferAndRsm& inputs, EffectCache* cache);
// contact: the shadow term with screen-space contact shadows added; with depth peeling's second
// layer (valid or not), an occluder is a sample between the two layers.
graph::ImageRef addContactPass(PassSetup& setup, const GBufferAndRsm& inputs,
                               graph::ImageRef shadow, graph::ImageRef secondLayer);
// peel: the second depth layer (world position of the next surface behind the G-buffer's).
graph::ImageRef addPeelPass(PassSetup& setup, const GBufferAndRsm& inputs);
// direct: spot-light radiance times the shadow term.
graph::ImageRef addDirectPass(PassSetup& setup, const GBufferAndRsm& inputs,
                              graph::ImageRef shadow);

// ao: visibility of the hemisphere within the AO radius (1 = open).
graph::ImageRef addAoPass(PassSetup& setup, const GBufferAndRsm& inputs, EffectCache* cache);

// The push constants of the indirect light's passes this frame (every method's gather, the
// upsampling, the filter's axes; the filter's axis left 0): the pattern's turn, scale and
// radial place, the sampling radius and the visibility march's start, the cache's state;
// `gather` is the size of the image the gather writes.
shader::IndirectConstants indirectConstants(const PassSetup& setup, const EffectCache* cache,
                                            VkExtent2D gather);

// indirect (half resolution) + upsample, indirect_method 0: one-bounce irradiance / pi from
// the RSM's VPLs.
graph::ImageRef addIndirectPasses(PassSetup& setup, const GBufferAndRsm& inputs,
                                  EffectCache* cache);

// indirect.flux + indirect.vpls, indirect_method 2: the RSM clustered into a coarser map of
// VPLs, and the list of VPLs drawn this frame in proportion to their flux.
struct FluxVpls {
    graph::ImageRef position, normal, flux, list;
};
FluxVpls addFluxVplPasses(PassSetup& setup, const GBufferAndRsm& inputs, EffectCache* cache);

// indirect (interleaved VPL subsets) + indirect.filter_x + indirect.filter_y: the same light,
// indirect_method 1; with `fluxVpls` (method 2) the flux's VPLs beside the pattern's.
graph::ImageRef addInterleavedIndirectPasses(PassSetup& setup, const GBufferAndRsm& inputs,
                                             EffectCache* cache,
                                             const FluxVpls* fluxVpls = nullptr);

// ssdo: directionally occluded sky light plus one bounce, as radiance.
// `secondLayer` (valid with depth peeling) makes its occlusion test two-layered.
graph::ImageRef addSsdoPass(PassSetup& setup, const GBufferAndRsm& inputs, graph::ImageRef direct,
                            graph::ImageRef secondLayer, EffectCache* cache);

// The screen-space terms the composite adds up; an invalid ref is an effect turned off.
struct LightingTerms {
    graph::ImageRef direct, shadow, ao, indirect, ssdo;
    graph::ImageRef skyVisibility; // the sky's visibility beyond the screen
    graph::ImageRef secondLayer;   // depth peeling's, for its debug view
};

// sky.maps + sky_visibility: the fraction of the sky's light reaching each pixel past the
// occluders beyond the AO's radius, from depth maps of the scene over the sky's directions.
graph::ImageRef addSkyVisibilityPasses(PassSetup& setup, const GBufferAndRsm& inputs);

struct CompositeOutputs {
    graph::ImageRef hdr, ldr;
};
// composite: HDR radiance, tonemapped sRGB image, or the debug view PassSetup::view names, at
// the output's size (the screen images less their guard band).
CompositeOutputs addCompositePass(PassSetup& setup, const GBufferAndRsm& inputs,
                                  const LightingTerms& terms);

// The whole frame, every pass above in order, as the scene's settings ask (frame.cpp).
void addFramePasses(PassSetup& setup);

} // namespace ssgi
