// The passes that rasterise the whole scene: the G-buffer (camera view) and the reflective
// shadow map (light view). Both are colour targets and a depth target, the scene drawn once.
// Neither keeps world positions: the G-buffer's follow from its view depth (R32F;
// gbuffer_position.glsl), the RSM's from the distance along the light's axis in its VPL texels
// (rsm_vpl.glsl).
#pragma once

#include "graph/frame_graph.h"
#include "passes/frame_build.h"

#include <optional>
#include <string>
#include <vector>

namespace ssgi {

struct SceneTarget {
    const char* suffix; // the image is the pass's name + suffix
    VkFormat format;
};
struct SceneTargets {
    std::vector<graph::ImageRef> colors; // in the fragment shader's order
    graph::ImageRef depth;
};
// How a scene pass draws the instances of opaque materials (no alpha mask).
enum class OpaqueDraws {
    Shaded,    // with the pass's fragment shader, as the alpha-masked ones
    DepthOnly, // with no fragment shader: a pass without colour targets whose fragment shader
               // only tests the alpha mask (scene_pass.cpp says why)
};
// A scene pipeline's depth-only twin for its opaque draws: no fragment shader, and of its
// bindings only binding 0, the view's uniforms, which is all the scene's vertex shaders read.
vk::GraphicsPipelineDesc depthOnly(vk::GraphicsPipelineDesc desc);
// What a scene pass's depth target is for.
enum class DepthTarget {
    Read,     // later passes read it (the RSM's and the shadow maps': the shadow test)
    DrawOnly, // it serves the pass's own draw alone (the G-buffer's): transient, kept by nothing
};
// `enabled` (optional) is asked each frame whether to draw; the targets of a pass that may be
// skipped persist from frame to frame (but a DrawOnly depth). With `firstTargetHistory`, the
// first colour target is a history pair (colors[0] is its current side), whose id is written
// there.
SceneTargets addScenePass(FrameBuild& build, const std::string& name, const std::string& shader,
                          VkExtent2D extent, const std::vector<SceneTarget>& targets,
                          graph::EnabledFn enabled = {},
                          std::optional<uint32_t>* firstTargetHistory = nullptr,
                          OpaqueDraws opaqueDraws = OpaqueDraws::Shaded,
                          DepthTarget depthTarget = DepthTarget::Read);

// gbuffer: view depth (0 where nothing was drawn), normal, albedo, depth.
struct GBuffer {
    graph::ImageRef viewDepth, normal, albedo, depth;
};
GBuffer addGBufferPass(FrameBuild& build);
// rsm: one VPL a texel (RGBA32UI: albedo, the light's share, normal, distance along the light's
// axis; rsm_vpl.glsl) and the depth target (the shadow map). Drawn on the frames whose
// FrameState::drawRsm says the light changed since it was last drawn.
struct Rsm {
    graph::ImageRef vpls, depth;
};
Rsm addRsmPass(FrameBuild& build);
// When the light's maps (the RSM, the shadow map and its back faces) are drawn: every frame
// without the cache; with it, on the frames FrameState::drawRsm names (the first, and after the
// light moved), the maps persisting in between.
graph::EnabledFn onLightFrames(const FrameBuild& build);
// shadow_map: the light's depth at shadow_map_size for the shadow test, drawn on the RSM's
// frames; where the sizes are equal, the RSM's own depth.
graph::ImageRef addShadowMapPass(FrameBuild& build, const Rsm& rsm);
// shadow_map_back: the depth of the nearest surface facing away from the light, at half
// shadow_map_size, for the shadow test's horizons (shadow_variant 1); drawn on the map's frames.
graph::ImageRef addShadowMapBackPass(FrameBuild& build);

struct GBufferAndRsm {
    GBuffer gbuffer;
    Rsm rsm;
    graph::ImageRef shadowMap;     // addShadowMapPass
    graph::ImageRef shadowMapBack; // addShadowMapBackPass (shadow_variant 1; else invalid)
    // addLightDepthMinPass, valid where the bounce's visibility test asks the light.
    graph::ImageRef lightDepthMin;
    // Depth peeling's second layer (peel_pass.cpp: the world position of the nearest surface
    // behind the G-buffer's, w = 0 where none), valid where depth_peeling is on and a pass
    // tests occlusion with it (frame.cpp).
    graph::ImageRef secondLayer;
};

} // namespace ssgi
