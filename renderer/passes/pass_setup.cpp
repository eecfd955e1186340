#include "passes/pass_setup.h"

namespace ssgi {

const vk::Pipeline& PassSetup::computePipeline(const std::string& shader, uint32_t sampled,
                                               uint32_t storage, uint32_t pushSize,
                                               const vk::Specialization& spec, uint32_t uniforms) {
    std::vector<VkDescriptorType> bindings = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER};
    bindings.insert(bindings.end(), sampled, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    bindings.insert(bindings.end(), storage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    bindings.insert(bindings.end(), uniforms, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
    pipelines.push_back(vk::createComputePipeline(ctx, shader, bindings, pushSize, spec));
    return pipelines.back();
}

} // namespace ssgi
