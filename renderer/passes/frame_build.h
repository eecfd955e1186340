// What every pass is built from: the device, the graph to add itself to, the scene and its copy
// on the device, the frame's uniforms and samplers, the frame's sizes, the pipelines the passes use
// (the Renderer's store), the buffers they made (owned here, destroyed with it), and the cached
// effects' histories. Made once by the Renderer with the frame's passes and left as it is from then
// on: what changes from frame to frame is the FrameState the graph hands to every pass
// (frame_state.h). Owned by the Renderer, so the passes' callbacks may keep a reference to it.
#pragma once

#include "cache/cache.h"
#include "graph/frame_graph.h"
#include "passes/compute_pass.h"
#include "scene/scene.h"
#include "scene_gpu.h"
#include "vk/pipeline.h"
#include "vk/pipeline_store.h"
#include "vk/resources.h"

#include <map>
#include <string>
#include <vector>

namespace ssgi {

// A lighting term the composite adds up: its image, under its view's name (views.h), and how it
// enters the sum (TERM_* of shared.h, from the view table).
struct CompositeTerm {
    std::string view;
    int role;
    graph::ImageRef image;
};

class FrameBuild {
public:
    // The frame's uniforms and both samplers are made here; the passes are added by
    // addFramePasses (passes.h).
    // The pipelines come from `pipelines` (the Renderer's, which may outlive this build).
    FrameBuild(vk::Context& ctx, graph::FrameGraph& graph, const SceneGpu& sceneGpu,
               vk::PipelineStore& pipelines, const Scene& scene, VkExtent2D size,
               uint32_t guardBand, VkExtent2D rsmSize, const glm::dvec3& gpuOrigin);
    ~FrameBuild(); // the device must be idle
    FrameBuild(const FrameBuild&) = delete;
    FrameBuild& operator=(const FrameBuild&) = delete;

    vk::Context& ctx;
    graph::FrameGraph& graph;
    const SceneGpu& sceneGpu;
    const Scene& scene;         // its settings, light, sky and bounds
    const Settings& settings;   // scene.settings
    const VkExtent2D size;      // every screen image: the output and the guard band
    const uint32_t guardBand;   // pixels beyond each edge of the output (guard_band)
    const VkExtent2D rsmSize;   // the reflective shadow map
    const glm::dvec3 gpuOrigin; // the world point at the GPU's origin (renderer.cpp)
    vk::Buffer frameUniforms;   // shader::FrameUniforms, written by the Renderer each frame
    VkSampler nearestSampler = VK_NULL_HANDLE;
    VkSampler linearSampler = VK_NULL_HANDLE;
    CacheSet caches; // empty when caching is off
    // The lighting terms the passes made, in the order they are added up (addCompositeTerm).
    std::vector<CompositeTerm> compositeTerms;

    // Where the output ("hdr", "ldr") lies in the screen images: the guard band in from each edge.
    VkRect2D output() const {
        return {{int32_t(guardBand), int32_t(guardBand)},
                {size.width - 2 * guardBand, size.height - 2 * guardBand}};
    }
    // Hands the composite a lighting term: `image` under `view`, a term's view of the view table
    // (views.h), which says how it enters the sum; terms are added up in the order given. Throws
    // std::logic_error for a view that is not a term's, a term given twice, or more terms than
    // the composite's slots (COMPOSITE_TERMS).
    void addCompositeTerm(const std::string& view, graph::ImageRef image);
    // A compute pipeline for `desc` at `spec` (its own, or its restart variant: compute_pass.h),
    // made once and shared by every pass that asks for the same shader, layout and
    // specialization (the interleaved filter's two axes), and by the builds of a renderer made
    // from this one's parts (vk/pipeline_store.h).
    const vk::Pipeline& computePipeline(const ComputePassDesc& desc,
                                        const std::vector<vk::LayoutBinding>& layout,
                                        const vk::Specialization& spec) {
        return pipelines_.compute(desc.shader, layout, desc.pushSize, spec);
    }
    // A graphics pipeline, shared likewise.
    const vk::Pipeline& graphicsPipeline(const vk::GraphicsPipelineDesc& desc) {
        return pipelines_.graphics(desc);
    }
    // A host-visible uniform buffer holding `bytes`, destroyed with the build.
    const vk::Buffer& uniformBuffer(const void* data, VkDeviceSize bytes);
    // A device buffer of `bytes` for `usage`, destroyed with the build.
    const vk::Buffer& deviceBuffer(VkDeviceSize bytes, VkBufferUsageFlags usage);
    // A host-visible storage buffer of `bytes` (zero), destroyed with the build; a pass that
    // writes it when recording may, since the Renderer waits for each frame before the next.
    const vk::Buffer& storageBuffer(VkDeviceSize bytes);

private:
    void release(); // what the destructor gives back; idempotent
    vk::PipelineStore& pipelines_;
    std::deque<vk::Buffer> buffers_;
};

} // namespace ssgi
