// What every pass needs to set itself up: the device, the graph to add itself to, the scene on
// the device, the frame's uniforms and samplers, and the frame's sizes. Owned by the Renderer,
// so the passes' record functions may keep a pointer to it.
#pragma once

#include "graph/frame_graph.h"
#include "scene_gpu.h"
#include "vk/pipeline.h"

#include <vector>

namespace ssgi {

struct PassSetup {
    vk::Context& ctx;
    graph::FrameGraph& graph;
    const SceneGpu& scene;
    vk::Buffer frameUniforms;
    VkSampler nearestSampler = VK_NULL_HANDLE;
    VkSampler linearSampler = VK_NULL_HANDLE;
    VkExtent2D size{};                   // the output image
    VkExtent2D rsmSize{};                // the reflective shadow map
    std::vector<vk::Pipeline> pipelines; // destroyed with the renderer
};

// The G-buffer (camera view) and the reflective shadow map (light view) are the same kind of
// pass: three colour targets and a depth target, the whole scene drawn once.
struct SceneTargets {
    graph::ImageRef position, normal, third, depth; // third: albedo (G-buffer) or flux (RSM)
};
SceneTargets addScenePass(PassSetup& setup, const std::string& name, const std::string& shader,
                          VkExtent2D extent, VkFormat thirdFormat);

// gbuffer: world position (w = 1 on geometry), normal, albedo, depth.
SceneTargets addGBufferPass(PassSetup& setup);
// rsm: light-view world position, normal, reflected flux, depth.
SceneTargets addRsmPass(PassSetup& setup);

struct GBufferAndRsm {
    SceneTargets gbuffer, rsm;
};
// direct: spot-light radiance with a hard shadow-map test.
graph::ImageRef addDirectPass(PassSetup& setup, const GBufferAndRsm& inputs);

struct CompositeOutputs {
    graph::ImageRef hdr, ldr;
};
// composite: HDR radiance, tonemapped sRGB image, or a debug view.
CompositeOutputs addCompositePass(PassSetup& setup, const GBufferAndRsm& inputs,
                                  graph::ImageRef direct, int view);

} // namespace ssgi
