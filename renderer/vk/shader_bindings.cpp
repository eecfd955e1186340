#include "vk/shader_bindings.h"

#include "vk/context.h"

#include <set>

namespace ssgi::vk {

namespace {

// The SPIR-V instructions read here (SPIR-V specification, section 3).
enum Op : uint32_t {
    OpName = 5,
    OpExecutionMode = 16,
    OpConstant = 43,
    OpExecutionModeId = 331,
    OpTypeImage = 25,
    OpTypeSampledImage = 27,
    OpTypeArray = 28,
    OpTypeRuntimeArray = 29,
    OpTypePointer = 32,
    OpVariable = 59,
    OpDecorate = 71,
};
enum Decoration : uint32_t {
    DecorationBlock = 2,
    DecorationBufferBlock = 3,
    SpecId = 1,
    NonWritable = 24,
    Binding = 33,
    Set = 34
};
enum StorageClass : uint32_t { UniformConstant = 0, Uniform = 2, StorageBuffer = 12 };
enum ExecutionMode : uint32_t { LocalSize = 17, LocalSizeId = 38 };

// The storage image formats this project's images have: a format's Image Format operand in
// SPIR-V (specification, 3.11), its Vulkan format, and how GLSL spells it (for the messages).
struct StorageFormat {
    uint32_t spirv;
    VkFormat vulkan;
    const char* glsl;
};
constexpr StorageFormat kStorageFormats[] = {{1, VK_FORMAT_R32G32B32A32_SFLOAT, "rgba32f"},
                                             {2, VK_FORMAT_R16G16B16A16_SFLOAT, "rgba16f"},
                                             {3, VK_FORMAT_R32_SFLOAT, "r32f"},
                                             {4, VK_FORMAT_R8G8B8A8_UNORM, "rgba8"},
                                             {6, VK_FORMAT_R32G32_SFLOAT, "rg32f"},
                                             {7, VK_FORMAT_R16G16_SFLOAT, "rg16f"},
                                             {9, VK_FORMAT_R16_SFLOAT, "r16f"},
                                             {30, VK_FORMAT_R32G32B32A32_UINT, "rgba32ui"},
                                             {35, VK_FORMAT_R32G32_UINT, "rg32ui"},
                                             {33, VK_FORMAT_R32_UINT, "r32ui"},
                                             {39, VK_FORMAT_R8_UINT, "r8ui"}};

// The Vulkan format an Image Format operand names; UNDEFINED for Unknown and the rest.
VkFormat vulkanFormat(uint32_t imageFormat) {
    for (const StorageFormat& f : kStorageFormats)
        if (f.spirv == imageFormat) return f.vulkan;
    return VK_FORMAT_UNDEFINED;
}

std::string formatName(VkFormat format) {
    for (const StorageFormat& f : kStorageFormats)
        if (f.vulkan == format) return f.glsl;
    return "VkFormat " + std::to_string(int(format));
}

// Calls visit(op, operands, operand count) for each instruction after the module's header.
template <typename Visit> void forEachInstruction(const uint32_t* code, size_t words, Visit visit) {
    for (size_t i = 5; i < words;) {
        const uint32_t count = code[i] >> 16, op = code[i] & 0xffff;
        if (count == 0 || i + count > words) break;
        visit(op, code + i + 1, count - 1);
        i += count;
    }
}

} // namespace

// A literal string operand: UTF-8 bytes packed four to a word, NUL-terminated.
static std::string literalString(const uint32_t* words, size_t count) {
    std::string s;
    for (size_t i = 0; i < count; ++i)
        for (int b = 0; b < 4; ++b) {
            const char c = char((words[i] >> (8 * b)) & 0xff);
            if (c == 0) return s;
            s += c;
        }
    return s;
}

std::map<uint32_t, ShaderBinding> shaderBindings(const uint32_t* code, size_t words, uint32_t set) {
    std::map<uint32_t, uint32_t> bindingOf, setOf;
    std::map<uint32_t, std::string> nameOf;
    std::set<uint32_t> bufferBlocks;          // structs decorated BufferBlock (old-style SSBOs)
    std::set<uint32_t> nonWritable;           // variables decorated NonWritable (readonly)
    std::map<uint32_t, uint32_t> imageUsage;  // OpTypeImage id -> Sampled operand (1 or 2)
    std::map<uint32_t, uint32_t> imageFormat; // OpTypeImage id -> Image Format operand
    std::set<uint32_t> sampledImages;         // OpTypeSampledImage ids
    std::map<uint32_t, uint32_t> elementOf;   // array type -> element type
    std::map<uint32_t, std::pair<uint32_t, uint32_t>> pointers; // id -> storage class, pointee
    std::vector<std::pair<uint32_t, uint32_t>> variables;       // id, pointer type
    forEachInstruction(code, words, [&](uint32_t op, const uint32_t* w, uint32_t operands) {
        switch (op) {
        case OpName:
            nameOf[w[0]] = literalString(w + 1, operands - 1);
            break;
        case OpDecorate:
            if (w[1] == Binding) bindingOf[w[0]] = w[2];
            if (w[1] == Set) setOf[w[0]] = w[2];
            if (w[1] == DecorationBufferBlock) bufferBlocks.insert(w[0]);
            if (w[1] == NonWritable) nonWritable.insert(w[0]);
            break;
        case OpTypeImage:
            imageUsage[w[0]] = w[6];
            imageFormat[w[0]] = w[7];
            break;
        case OpTypeSampledImage:
            sampledImages.insert(w[0]);
            break;
        case OpTypeArray:
        case OpTypeRuntimeArray:
            elementOf[w[0]] = w[1];
            break;
        case OpTypePointer:
            pointers[w[0]] = {w[1], w[2]};
            break;
        case OpVariable:
            variables.push_back({w[1], w[0]});
            break;
        default:
            break;
        }
    });
    std::map<uint32_t, ShaderBinding> result;
    for (const auto& [id, pointerType] : variables) {
        if (!bindingOf.count(id) || (setOf.count(id) ? setOf[id] : 0) != set) continue;
        const auto pointer = pointers.find(pointerType);
        if (pointer == pointers.end()) continue;
        auto [storage, type] = pointer->second;
        while (elementOf.count(type))
            type = elementOf[type];
        VkDescriptorType descriptor;
        if (storage == Uniform)
            descriptor = bufferBlocks.count(type) ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                                  : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        else if (storage == StorageBuffer)
            descriptor = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        else if (storage == UniformConstant && sampledImages.count(type))
            descriptor = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        else if (storage == UniformConstant && imageUsage.count(type))
            descriptor = imageUsage[type] == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                               : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        else
            continue;
        std::string name = nameOf.count(id) ? nameOf[id] : "";
        if (name.empty() && nameOf.count(type)) name = nameOf[type]; // an anonymous block
        const VkFormat format = descriptor == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                    ? vulkanFormat(imageFormat[type])
                                    : VK_FORMAT_UNDEFINED;
        result[bindingOf[id]] = {descriptor, name, !nonWritable.count(id), format};
    }
    return result;
}

std::map<std::string, uint32_t> shaderSpecConstants(const uint32_t* code, size_t words) {
    std::map<uint32_t, std::string> nameOf;
    std::map<uint32_t, uint32_t> specIdOf;
    forEachInstruction(code, words, [&](uint32_t op, const uint32_t* w, uint32_t operands) {
        if (op == OpName) nameOf[w[0]] = literalString(w + 1, operands - 1);
        if (op == OpDecorate && w[1] == SpecId) specIdOf[w[0]] = w[2];
    });
    std::map<std::string, uint32_t> result;
    for (const auto& [id, specId] : specIdOf)
        result[nameOf.count(id) ? nameOf[id] : "constant " + std::to_string(specId)] = specId;
    return result;
}

WorkgroupSize shaderWorkgroupSize(const uint32_t* code, size_t words) {
    // Literal sizes (LocalSize), or the ids of constants that hold them (LocalSizeId, which
    // glslang writes for Vulkan 1.3).
    WorkgroupSize size;
    std::map<uint32_t, uint32_t> constants; // id -> a 32-bit constant's value
    uint32_t xId = 0, yId = 0;
    forEachInstruction(code, words, [&](uint32_t op, const uint32_t* w, uint32_t operands) {
        if (op == OpConstant && operands == 3) constants[w[1]] = w[2];
        if (op == OpExecutionMode && operands >= 4 && w[1] == LocalSize) size = {w[2], w[3]};
        if (op == OpExecutionModeId && operands >= 4 && w[1] == LocalSizeId) {
            xId = w[2];
            yId = w[3];
        }
    });
    if (constants.count(xId) && constants.count(yId)) size = {constants[xId], constants[yId]};
    return size;
}

std::string descriptorTypeName(VkDescriptorType type) {
    switch (type) {
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        return "a uniform buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
        return "a storage buffer";
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
        return "a sampled image (sampler2D)";
    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
        return "a sampled image without sampler";
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
        return "a storage image (image2D)";
    default:
        return "descriptor type " + std::to_string(int(type));
    }
}

void checkBindings(const std::string& shader, const std::map<uint32_t, ShaderBinding>& declared,
                   const std::vector<LayoutBinding>& layout) {
    auto named = [](const std::string& name) { return name.empty() ? "" : " " + name; };
    for (const auto& [binding, found] : declared) {
        const std::string what = descriptorTypeName(found.type) + named(found.name);
        if (binding >= layout.size())
            throw VulkanError(shader + " reads binding " + std::to_string(binding) + " (" + what +
                              ") of set 0, which the pass's layout (" +
                              std::to_string(layout.size()) + " bindings) lacks");
        const LayoutBinding& expected = layout[binding];
        if (expected.type != found.type)
            throw VulkanError(shader + " binding " + std::to_string(binding) + " is " + what +
                              ", the pass's layout makes it " + descriptorTypeName(expected.type) +
                              named(expected.name));
        if (!expected.name.empty() && expected.name != found.name)
            throw VulkanError(shader + " binding " + std::to_string(binding) + " is " + what +
                              ", the pass declares " + expected.name + " there");
        if (expected.readOnly && found.type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE && found.writable)
            throw VulkanError(shader + " binding " + std::to_string(binding) + " is " + what +
                              ", which it may write (not declared readonly), and the pass takes "
                              "it as read only: its writes would go unsynchronized");
        if (found.format != VK_FORMAT_UNDEFINED && expected.format != VK_FORMAT_UNDEFINED &&
            found.format != expected.format)
            throw VulkanError(shader + " binding " + std::to_string(binding) + " is " + what +
                              " declared as " + formatName(found.format) +
                              ", and the pass binds an image of " + formatName(expected.format));
    }
    for (uint32_t binding = 0; binding < layout.size(); ++binding)
        if (!declared.count(binding))
            throw VulkanError("the pass's layout has binding " + std::to_string(binding) + " (" +
                              descriptorTypeName(layout[binding].type) +
                              named(layout[binding].name) + ") that " + shader + " never declares");
}

} // namespace ssgi::vk
