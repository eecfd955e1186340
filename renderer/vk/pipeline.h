// Pipelines built from the SPIR-V the build compiles, with one push-descriptor set (set 0) per
// pipeline, an optional second set (the scene's textures), and push constants.
#pragma once

#include "vk/context.h"
#include "vk/shader_bindings.h"

#include <deque>
#include <string>
#include <vector>

namespace ssgi::vk {

struct Pipeline {
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSetLayout pushSetLayout = VK_NULL_HANDLE;
    VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
    uint32_t pushConstantSize = 0;
    uint32_t bindingCount = 0;     // set 0's
    VkShaderStageFlags stages = 0; // those the pipeline has: its layout's and push constants'
    WorkgroupSize workgroup;       // a compute shader's, as its SPIR-V declares it
};

// Structural settings (kernel sizes, variants) go in as specialization constants, by the names
// the shader gives them.
struct SpecConstant {
    std::string name;
    int32_t value;
};
struct Specialization {
    std::vector<SpecConstant> constants;
};

// Set 0's layout is `bindings` (binding i is bindings[i]); the shader's own declarations must
// agree with it, names included where given (checkBindings), or this throws naming both. Each
// specialization constant the shader declares must be given by name, and no other.
Pipeline createComputePipeline(Context& ctx, const std::string& shader,
                               const std::vector<LayoutBinding>& bindings,
                               uint32_t pushConstantSize, const Specialization& spec = {});

// The vertex buffer's layout at binding 0: its stride and attributes. The caller's to give
// (the scene's vertices: scene_gpu.h sceneVertexInput), so this layer knows no vertex type.
struct VertexInput {
    uint32_t stride = 0;
    std::vector<VkVertexInputAttributeDescription> attributes;
};

struct GraphicsPipelineDesc {
    // No fragment shader (empty): a depth-only pipeline of the vertex stage alone, which takes
    // no colour formats; its bindings are then the vertex shader's.
    std::string vertexShader, fragmentShader;
    VertexInput vertices;
    std::vector<VkFormat> colorFormats;
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    std::vector<LayoutBinding> bindings;                     // set 0, push descriptors
    VkDescriptorSetLayout textureSetLayout = VK_NULL_HANDLE; // set 1, optional
    uint32_t pushConstantSize = 0;
    // Each stage's specialization constants, as createComputePipeline takes them.
    Specialization vertexSpec, fragmentSpec;
};

// Vertex input as `desc.vertices` says; no culling (our surfaces are two-sided).
Pipeline createGraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc);
void destroyPipeline(const Context& ctx, Pipeline& pipeline);

// Descriptor writes for one push; binding numbers are the shader's.
class Descriptors {
public:
    Descriptors& storageImage(uint32_t binding, VkImageView view);
    Descriptors& sampledImage(uint32_t binding, VkImageView view, VkSampler sampler,
                              VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    Descriptors& uniformBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize size);
    Descriptors& storageBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize size);
    void push(const Context& ctx, VkCommandBuffer cmd, const Pipeline& pipeline);

private:
    std::vector<VkWriteDescriptorSet> writes_;
    std::deque<VkDescriptorImageInfo> images_;
    std::deque<VkDescriptorBufferInfo> buffers_;
};

// Binds, pushes constants (size checked against the pipeline) and dispatches enough of the
// shader's workgroups to cover width x height.
// As dispatch, with the workgroup counts read by the device from `buffer` at `offset` (a
// VkDispatchIndirectCommand) rather than given.
void dispatchIndirect(VkCommandBuffer cmd, const Pipeline& pipeline, VkBuffer buffer,
                      VkDeviceSize offset, const void* pushConstants, uint32_t pushSize);
void dispatch(VkCommandBuffer cmd, const Pipeline& pipeline, uint32_t width, uint32_t height,
              const void* pushConstants, uint32_t pushSize);

template <typename T>
void dispatch(VkCommandBuffer cmd, const Pipeline& pipeline, uint32_t width, uint32_t height,
              const T& pushConstants) {
    dispatch(cmd, pipeline, width, height, &pushConstants, sizeof(T));
}

VkSampler createSampler(const Context& ctx, VkFilter filter, VkSamplerAddressMode address);
// One level, each filter and each axis's addressing as given.
VkSampler createSampler(const Context& ctx, VkFilter magnify, VkFilter minify,
                        VkSamplerAddressMode addressU, VkSamplerAddressMode addressV);

} // namespace ssgi::vk
