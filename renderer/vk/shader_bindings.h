// What a shader itself declares in a descriptor set, read from its SPIR-V (the binding and
// descriptor-set decorations of its resource variables), so that a pipeline's layout can be
// held to it: a pass's declared bindings and the shader's `layout(binding = N)` are written in
// two places, and this is where they must agree (the pipelines check it when they are made).
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace ssgi::vk {

// Binding number -> descriptor type of every resource in descriptor set `set` (uniform buffers,
// storage buffers, combined image samplers, sampled and storage images).
std::map<uint32_t, VkDescriptorType> shaderBindings(const uint32_t* code, size_t words,
                                                    uint32_t set);

// Throws VulkanError naming the shader and the binding where `layout` (binding i has type
// layout[i]) and `declared` (what the shaders read) disagree: a binding of another type, one the
// shader reads that the layout lacks, or one the layout has that the shader never declares.
void checkBindings(const std::string& shader, const std::map<uint32_t, VkDescriptorType>& declared,
                   const std::vector<VkDescriptorType>& layout);

std::string descriptorTypeName(VkDescriptorType type);

} // namespace ssgi::vk
