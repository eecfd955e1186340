#include "passes/compute_pass.h"

#include "passes/frame_build.h"

namespace ssgi {

static bool isSampled(graph::Use use) {
    return use == graph::Use::Sampled;
}

static bool isStorage(graph::Use use) {
    return use == graph::Use::StorageRead || use == graph::Use::StorageWrite ||
           use == graph::Use::StorageReadWrite;
}

void ComputeRecorder::dispatch(uint32_t width, uint32_t height, const void* constants,
                               uint32_t size) const {
    pushDescriptors();
    vk::dispatch(pass_.cmd, pipeline_, width, height, constants, size);
}

void ComputeRecorder::dispatchIndirect(VkBuffer buffer, VkDeviceSize offset, const void* constants,
                                       uint32_t size) const {
    pushDescriptors();
    vk::dispatchIndirect(pass_.cmd, pipeline_, buffer, offset, constants, size);
}

void ComputeRecorder::pushDescriptors() const {
    const FrameBuild& build = build_;
    vk::Descriptors d;
    d.uniformBuffer(0, build.frameUniforms.buffer, build.frameUniforms.size);
    uint32_t binding = 1;
    for (const ShaderImage& i : desc_.images) {
        const VkImageView view = pass_.image(i.image).view;
        if (isSampled(i.use))
            d.sampledImage(binding++, view, i.sampler ? i.sampler : build.nearestSampler);
        else
            d.storageImage(binding++, view);
    }
    for (const ShaderBuffer& b : desc_.uniforms) {
        if (b.storage)
            d.storageBuffer(binding++, b.buffer.buffer, b.buffer.size);
        else
            d.uniformBuffer(binding++, b.buffer.buffer, b.buffer.size);
    }
    d.push(build.ctx, pass_.cmd, pipeline_);
}

void addComputePass(FrameBuild& build, ComputePassDesc desc, ComputeRecordFn record,
                    graph::EnabledFn enabled) {
    std::vector<vk::LayoutBinding> layout = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, "FrameBlock"}};
    std::vector<graph::ImageUse> uses;
    for (const ShaderImage& i : desc.images) {
        if (!isSampled(i.use) && !isStorage(i.use))
            throw std::logic_error("pass " + desc.name + " binds " + i.name +
                                   " for a use a compute shader cannot bind");
        // A storage image's format, which a format the shader declares must match.
        const VkFormat format =
            isStorage(i.use) ? build.graph.image(i.image).format : VK_FORMAT_UNDEFINED;
        layout.push_back({isSampled(i.use) ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                           : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                          i.name, i.use == graph::Use::StorageRead, format});
        uses.push_back({i.image, i.use});
    }
    for (const ShaderBuffer& b : desc.uniforms)
        layout.push_back(
            {b.storage ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
             b.name, b.storage});
    const vk::Pipeline pipeline = build.computePipeline(desc, layout, desc.spec);
    const vk::Pipeline restartPipeline =
        desc.restartSpec ? build.computePipeline(desc, layout, *desc.restartSpec) : pipeline;
    const std::string name = desc.name;
    build.graph.addPass(
        name, graph::PassKind::Compute, std::move(uses),
        [&build, desc = std::move(desc), record = std::move(record), pipeline,
         restartPipeline](const graph::PassContext& pc) {
            record(ComputeRecorder(build, pc, desc, pipeline, restartPipeline));
        },
        std::move(enabled));
}

} // namespace ssgi
