#include "passes/frame_build.h"

#include "passes/views.h"
#include "shared.h"

#include <cstring>
#include <stdexcept>

namespace ssgi {

FrameBuild::FrameBuild(vk::Context& ctx, graph::FrameGraph& graph, const SceneGpu& sceneGpu,
                       vk::PipelineStore& pipelines, const Scene& scene, VkExtent2D size,
                       uint32_t guardBand, VkExtent2D rsmSize, const glm::dvec3& gpuOrigin)
    : ctx(ctx), graph(graph), sceneGpu(sceneGpu), scene(scene), settings(scene.settings),
      size(size), guardBand(guardBand), rsmSize(rsmSize), gpuOrigin(gpuOrigin),
      pipelines_(pipelines) {
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
    for (vk::Buffer& b : buffers_)
        vk::destroyBuffer(ctx, b);
    buffers_.clear();
    vk::destroyBuffer(ctx, frameUniforms);
    vkDestroySampler(ctx.device, nearestSampler, nullptr);
    vkDestroySampler(ctx.device, linearSampler, nullptr);
    nearestSampler = linearSampler = VK_NULL_HANDLE;
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
