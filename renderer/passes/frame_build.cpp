#include "passes/frame_build.h"

#include "passes/views.h"
#include "shared.h"

#include <cstring>
#include <stdexcept>

namespace ssgi {

FrameBuild::FrameBuild(vk::Context& ctx, graph::FrameGraph& graph, const SceneGpu& sceneGpu,
                       const Scene& scene, VkExtent2D size, uint32_t guardBand, VkExtent2D rsmSize,
                       const glm::dvec3& gpuOrigin)
    : ctx(ctx), graph(graph), sceneGpu(sceneGpu), scene(scene), settings(scene.settings),
      size(size), guardBand(guardBand), rsmSize(rsmSize), gpuOrigin(gpuOrigin) {
    try {
        frameUniforms = vk::createBuffer(ctx, sizeof(shader::FrameUniforms),
                                         VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
        nearestSampler =
            vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
        linearSampler =
            vk::createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    } catch (...) { // a constructor that throws runs no destructor: give back what was made
        release();
        throw;
    }
}

FrameBuild::~FrameBuild() {
    release();
}

void FrameBuild::release() {
    for (vk::Pipeline& p : pipelines_)
        vk::destroyPipeline(ctx, p);
    for (vk::Buffer& b : buffers_)
        vk::destroyBuffer(ctx, b);
    pipelines_.clear();
    buffers_.clear();
    vk::destroyBuffer(ctx, frameUniforms);
    vkDestroySampler(ctx.device, nearestSampler, nullptr);
    vkDestroySampler(ctx.device, linearSampler, nullptr);
    nearestSampler = linearSampler = VK_NULL_HANDLE;
}

const vk::Pipeline& FrameBuild::computePipeline(const ComputePassDesc& desc,
                                                const std::vector<vk::LayoutBinding>& layout) {
    std::string key = desc.shader + " push " + std::to_string(desc.pushSize) + " spec";
    for (const vk::SpecConstant& c : desc.spec.constants)
        key += " " + c.name + "=" + std::to_string(c.value);
    for (const vk::LayoutBinding& b : layout)
        key += " " + std::to_string(int(b.type)) + ":" + b.name + (b.readOnly ? ":readonly" : "");
    const auto found = computePipelines_.find(key);
    if (found != computePipelines_.end()) return pipelines_[found->second];
    pipelines_.push_back(
        vk::createComputePipeline(ctx, desc.shader, layout, desc.pushSize, desc.spec));
    computePipelines_[key] = pipelines_.size() - 1;
    return pipelines_.back();
}

vk::Pipeline FrameBuild::graphicsPipeline(const vk::GraphicsPipelineDesc& desc) {
    pipelines_.push_back(vk::createGraphicsPipeline(ctx, desc));
    return pipelines_.back();
}

void FrameBuild::addCompositeTerm(const std::string& view, graph::ImageRef image) {
    const ViewDef* def = findView(view);
    if (!def || def->view != VIEW_TERM || def->showsTerm)
        throw std::logic_error("addCompositeTerm: '" + view + "' is not a term's view (views.h)");
    for (const CompositeTerm& term : compositeTerms)
        if (term.view == view) throw std::logic_error("addCompositeTerm: '" + view + "' twice");
    if (compositeTerms.size() == COMPOSITE_TERMS)
        throw std::logic_error("addCompositeTerm: composite.comp binds " +
                               std::to_string(COMPOSITE_TERMS) + " terms, '" + view +
                               "' is one more");
    compositeTerms.push_back({view, def->role, image});
}

const vk::Buffer& FrameBuild::deviceBuffer(VkDeviceSize bytes, VkBufferUsageFlags usage) {
    buffers_.push_back(vk::createBuffer(ctx, bytes, usage, false));
    return buffers_.back();
}

const vk::Buffer& FrameBuild::uniformBuffer(const void* data, VkDeviceSize bytes) {
    buffers_.push_back(vk::createBuffer(ctx, bytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true));
    std::memcpy(buffers_.back().mapped, data, bytes);
    return buffers_.back();
}

const vk::Buffer& FrameBuild::storageBuffer(VkDeviceSize bytes) {
    buffers_.push_back(vk::createBuffer(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true));
    std::memset(buffers_.back().mapped, 0, bytes);
    return buffers_.back();
}

} // namespace ssgi
