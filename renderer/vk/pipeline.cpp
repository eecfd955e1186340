#include "vk/pipeline.h"

#include "vk/embedded_shaders.h"
#include "vk/shader_bindings.h"

#include <algorithm>
#include <cstddef>

namespace ssgi::vk {

static const EmbeddedShader& findShader(const std::string& name) {
    const auto& shaders = embeddedShaders();
    const auto found = std::find_if(shaders.begin(), shaders.end(),
                                    [&](const EmbeddedShader& s) { return name == s.name; });
    if (found == shaders.end())
        throw VulkanError("no shader " + name + " in this program (not in shaders/glsl/?)");
    return *found;
}

// Set 0's bindings as the shader declares them.
static std::map<uint32_t, ShaderBinding> declaredBindings(const std::string& name) {
    const EmbeddedShader& shader = findShader(name);
    return shaderBindings(shader.code, shader.bytes / sizeof(uint32_t), 0);
}

static VkShaderModule loadShader(const Context& ctx, const std::string& name) {
    const EmbeddedShader& shader = findShader(name);
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = shader.bytes;
    info.pCode = shader.code;
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(ctx.device, &info, nullptr, &module));
    return module;
}

static void createLayout(Context& ctx, Pipeline& p, const std::vector<LayoutBinding>& bindings,
                         VkDescriptorSetLayout textureSet, uint32_t pushSize) {
    std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
    for (uint32_t i = 0; i < bindings.size(); ++i)
        layoutBindings.push_back({i, bindings[i].type, 1, p.stages, nullptr});
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    setInfo.bindingCount = uint32_t(layoutBindings.size());
    setInfo.pBindings = layoutBindings.data();
    VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &setInfo, nullptr, &p.pushSetLayout));

    VkDescriptorSetLayout sets[2] = {p.pushSetLayout, textureSet};
    VkPushConstantRange range{p.stages, 0, pushSize};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = textureSet ? 2 : 1;
    layoutInfo.pSetLayouts = sets;
    layoutInfo.pushConstantRangeCount = pushSize ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    VK_CHECK(vkCreatePipelineLayout(ctx.device, &layoutInfo, nullptr, &p.layout));
    p.pushConstantSize = pushSize;
    p.bindingCount = uint32_t(bindings.size());
}

// The map entries that give each of `spec`'s constants to the shader's constant of that name;
// VulkanError naming the shader and the constant where one is given that the shader lacks, or
// one the shader declares is not given.
static std::vector<VkSpecializationMapEntry> specEntries(const std::string& name,
                                                         const Specialization& spec) {
    const EmbeddedShader& shader = findShader(name);
    std::map<std::string, uint32_t> declared =
        shaderSpecConstants(shader.code, shader.bytes / sizeof(uint32_t));
    std::vector<VkSpecializationMapEntry> entries;
    for (uint32_t i = 0; i < spec.constants.size(); ++i) {
        const auto found = declared.find(spec.constants[i].name);
        if (found == declared.end())
            throw VulkanError(name + " declares no specialization constant " +
                              spec.constants[i].name);
        entries.push_back({found->second, uint32_t(i * sizeof(int32_t)), sizeof(int32_t)});
        declared.erase(found);
    }
    if (!declared.empty())
        throw VulkanError(name + " declares specialization constant " + declared.begin()->first +
                          ", which the pass does not give");
    return entries;
}

Pipeline createComputePipeline(Context& ctx, const std::string& shader,
                               const std::vector<LayoutBinding>& bindings,
                               uint32_t pushConstantSize, const Specialization& spec) {
    checkBindings(shader, declaredBindings(shader), bindings);
    const std::vector<VkSpecializationMapEntry> entries = specEntries(shader, spec);
    std::vector<int32_t> values;
    for (const SpecConstant& c : spec.constants)
        values.push_back(c.value);
    VkSpecializationInfo specInfo{uint32_t(entries.size()), entries.data(),
                                  values.size() * sizeof(int32_t), values.data()};
    Pipeline p;
    p.bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
    p.stages = VK_SHADER_STAGE_COMPUTE_BIT;
    const EmbeddedShader& code = findShader(shader);
    p.workgroup = shaderWorkgroupSize(code.code, code.bytes / sizeof(uint32_t));
    createLayout(ctx, p, bindings, VK_NULL_HANDLE, pushConstantSize);

    VkShaderModule module = loadShader(ctx, shader);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = entries.empty() ? nullptr : &specInfo;
    info.layout = p.layout;
    VkResult result =
        vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline);
    vkDestroyShaderModule(ctx.device, module, nullptr);
    VK_CHECK(result);
    ctx.nameObject(VK_OBJECT_TYPE_PIPELINE, uint64_t(p.pipeline), shader);
    return p;
}

Pipeline createGraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc) {
    const bool fragment = !desc.fragmentShader.empty();
    const std::string shaders =
        fragment ? desc.vertexShader + " + " + desc.fragmentShader : desc.vertexShader;
    if (!fragment && !desc.colorFormats.empty())
        throw VulkanError(shaders + ": colour targets need a fragment shader");
    std::map<uint32_t, ShaderBinding> declared = declaredBindings(desc.vertexShader);
    if (fragment) // a binding both read is the same
        declared.merge(declaredBindings(desc.fragmentShader));
    checkBindings(shaders, declared, desc.bindings);
    Pipeline p;
    p.bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    p.stages = VK_SHADER_STAGE_VERTEX_BIT | (fragment ? VK_SHADER_STAGE_FRAGMENT_BIT : 0);
    createLayout(ctx, p, desc.bindings, desc.textureSetLayout, desc.pushConstantSize);

    // Each stage's constants: their map entries and values (empty for a stage that has none).
    struct StageSpec {
        std::vector<VkSpecializationMapEntry> entries;
        std::vector<int32_t> values;
        VkSpecializationInfo info{};
        const VkSpecializationInfo* get() {
            info = {uint32_t(entries.size()), entries.data(), values.size() * sizeof(int32_t),
                    values.data()};
            return entries.empty() ? nullptr : &info;
        }
    };
    StageSpec vertexSpec, fragmentSpec;
    vertexSpec.entries = specEntries(desc.vertexShader, desc.vertexSpec);
    for (const SpecConstant& c : desc.vertexSpec.constants)
        vertexSpec.values.push_back(c.value);
    if (fragment) {
        fragmentSpec.entries = specEntries(desc.fragmentShader, desc.fragmentSpec);
        for (const SpecConstant& c : desc.fragmentSpec.constants)
            fragmentSpec.values.push_back(c.value);
    }
    VkShaderModule vs = loadShader(ctx, desc.vertexShader);
    VkShaderModule fs = fragment ? loadShader(ctx, desc.fragmentShader) : VK_NULL_HANDLE;
    VkPipelineShaderStageCreateInfo stages[2] = {
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
         VK_SHADER_STAGE_VERTEX_BIT, vs, "main", vertexSpec.get()},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
         VK_SHADER_STAGE_FRAGMENT_BIT, fs, "main", fragmentSpec.get()}};

    VkVertexInputBindingDescription binding{0, desc.vertices.stride, VK_VERTEX_INPUT_RATE_VERTEX};
    VkPipelineVertexInputStateCreateInfo vertexInput{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertexInput.vertexBindingDescriptionCount = 1;
    vertexInput.pVertexBindingDescriptions = &binding;
    vertexInput.vertexAttributeDescriptionCount = uint32_t(desc.vertices.attributes.size());
    vertexInput.pVertexAttributeDescriptions = desc.vertices.attributes.data();

    VkPipelineInputAssemblyStateCreateInfo assembly{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{
        VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS;
    std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
    for (auto& b : blends)
        b.colorWriteMask = 0xF;
    VkPipelineColorBlendStateCreateInfo blend{
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = uint32_t(blends.size());
    blend.pAttachments = blends.data();
    VkDynamicState dynamics[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamics;

    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = uint32_t(desc.colorFormats.size());
    rendering.pColorAttachmentFormats = desc.colorFormats.data();
    rendering.depthAttachmentFormat = desc.depthFormat;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = fragment ? 2 : 1;
    info.pStages = stages;
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = p.layout;
    VkResult result =
        vkCreateGraphicsPipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline);
    vkDestroyShaderModule(ctx.device, vs, nullptr);
    if (fs) vkDestroyShaderModule(ctx.device, fs, nullptr);
    VK_CHECK(result);
    ctx.nameObject(VK_OBJECT_TYPE_PIPELINE, uint64_t(p.pipeline),
                   fragment ? desc.fragmentShader : desc.vertexShader);
    return p;
}

void destroyPipeline(const Context& ctx, Pipeline& p) {
    if (p.pipeline) vkDestroyPipeline(ctx.device, p.pipeline, nullptr);
    if (p.layout) vkDestroyPipelineLayout(ctx.device, p.layout, nullptr);
    if (p.pushSetLayout) vkDestroyDescriptorSetLayout(ctx.device, p.pushSetLayout, nullptr);
    p = {};
}

Descriptors& Descriptors::storageImage(uint32_t binding, VkImageView view) {
    images_.push_back({VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w.pImageInfo = &images_.back();
    writes_.push_back(w);
    return *this;
}

Descriptors& Descriptors::sampledImage(uint32_t binding, VkImageView view, VkSampler sampler,
                                       VkImageLayout layout) {
    images_.push_back({sampler, view, layout});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = &images_.back();
    writes_.push_back(w);
    return *this;
}

static VkWriteDescriptorSet bufferWrite(uint32_t binding, VkDescriptorType type,
                                        const VkDescriptorBufferInfo* info) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = type;
    w.pBufferInfo = info;
    return w;
}

Descriptors& Descriptors::uniformBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize size) {
    buffers_.push_back({buffer, 0, size});
    writes_.push_back(bufferWrite(binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &buffers_.back()));
    return *this;
}

Descriptors& Descriptors::storageBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize size) {
    buffers_.push_back({buffer, 0, size});
    writes_.push_back(bufferWrite(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &buffers_.back()));
    return *this;
}

void Descriptors::push(const Context& ctx, VkCommandBuffer cmd, const Pipeline& pipeline) {
    ctx.cmdPushDescriptorSet(cmd, pipeline.bindPoint, pipeline.layout, 0, uint32_t(writes_.size()),
                             writes_.data());
}

void dispatch(VkCommandBuffer cmd, const Pipeline& pipeline, uint32_t width, uint32_t height,
              const void* pushConstants, uint32_t pushSize) {
    if (pushSize != pipeline.pushConstantSize)
        throw VulkanError("dispatch: push constant size does not match the pipeline's");
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
    if (pushSize)
        vkCmdPushConstants(cmd, pipeline.layout, pipeline.stages, 0, pushSize, pushConstants);
    const WorkgroupSize group = pipeline.workgroup;
    vkCmdDispatch(cmd, (width + group.x - 1) / group.x, (height + group.y - 1) / group.y, 1);
}

void dispatchIndirect(VkCommandBuffer cmd, const Pipeline& pipeline, VkBuffer buffer,
                      VkDeviceSize offset, const void* pushConstants, uint32_t pushSize) {
    if (pushSize != pipeline.pushConstantSize)
        throw VulkanError("dispatch: push constant size does not match the pipeline's");
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
    if (pushSize)
        vkCmdPushConstants(cmd, pipeline.layout, pipeline.stages, 0, pushSize, pushConstants);
    vkCmdDispatchIndirect(cmd, buffer, offset);
}

VkSampler createSampler(const Context& ctx, VkFilter filter, VkSamplerAddressMode address) {
    return createSampler(ctx, filter, filter, address, address);
}

VkSampler createSampler(const Context& ctx, VkFilter magnify, VkFilter minify,
                        VkSamplerAddressMode addressU, VkSamplerAddressMode addressV) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = magnify;
    info.minFilter = minify;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = addressU;
    info.addressModeV = info.addressModeW = addressV;
    info.maxLod = 0.0f;
    VkSampler sampler;
    VK_CHECK(vkCreateSampler(ctx.device, &info, nullptr, &sampler));
    return sampler;
}

} // namespace ssgi::vk
