// What a shader itself declares in a descriptor set, read from its SPIR-V (the binding and
// descriptor-set decorations of its resource variables, and their names), so that a pipeline's
// layout can be held to it: a pass declares its bindings in C++ and the shader declares them in
// GLSL, and this is where the two must agree (the pipelines check it when they are made).
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace ssgi::vk {

// One resource of a descriptor set: its descriptor type and the name the shader gives it (the
// variable's; for a uniform or storage block, whose variable is usually anonymous, the block's).
struct ShaderBinding {
    VkDescriptorType type;
    std::string name;
    bool writable = true; // false where the shader declares it readonly (NonWritable)
    // A storage image's format as the shader declares it (layout(rgba16f) ...), or UNDEFINED
    // where it declares none (a write without a format) or the format is none this project uses.
    VkFormat format = VK_FORMAT_UNDEFINED;
};

// Binding number -> every resource in descriptor set `set` (uniform buffers, storage buffers,
// combined image samplers, sampled and storage images).
std::map<uint32_t, ShaderBinding> shaderBindings(const uint32_t* code, size_t words, uint32_t set);

// The specialization constants a shader declares (layout(constant_id = N) const int NAME): name
// -> constant id.
std::map<std::string, uint32_t> shaderSpecConstants(const uint32_t* code, size_t words);

// A compute shader's workgroup size (layout(local_size_x = X, local_size_y = Y) in); {1, 1} for
// a shader that declares none.
struct WorkgroupSize {
    uint32_t x = 1, y = 1;
};
WorkgroupSize shaderWorkgroupSize(const uint32_t* code, size_t words);

// One binding of a pipeline's layout: its type and, where the caller names it, the name the
// shader must give it (empty: only the type is checked); `readOnly`: the caller takes the
// shader never to write it (a frame graph's StorageRead), which the shader must then declare;
// `format`: a storage image's, which a format the shader declares must match (UNDEFINED: not
// known, not checked).
struct LayoutBinding {
    LayoutBinding(VkDescriptorType type, std::string name = {}, bool readOnly = false,
                  VkFormat format = VK_FORMAT_UNDEFINED)
        : type(type), name(std::move(name)), readOnly(readOnly), format(format) {}
    VkDescriptorType type;
    std::string name;
    bool readOnly;
    VkFormat format;
};

// Throws VulkanError naming the shader and the binding where `layout` (binding i is layout[i])
// and `declared` (what the shaders read) disagree: a binding of another type or another name,
// one the shader reads that the layout lacks, one the layout has that the shader never
// declares, or a storage image the layout takes as read-only that the shader may write
// (synchronization validation, and the GPU, count a dispatch's writable storage image as
// written, whatever the shader does with it), or a storage image whose declared format is not
// the bound image's (its texels would be read or written as another layout).
void checkBindings(const std::string& shader, const std::map<uint32_t, ShaderBinding>& declared,
                   const std::vector<LayoutBinding>& layout);

std::string descriptorTypeName(VkDescriptorType type);

} // namespace ssgi::vk
