// The pipelines hold a pass's declared bindings and specialization constants to what its shader
// declares (vk/shader_bindings): the reflection reads the shader's own layout, constants and
// workgroup size, and a layout or a constant that disagrees is refused at pipeline creation with
// the shader and the binding or constant named.
#include "support.h"

#include "scene_gpu.h"
#include "shared.h"
#include "vk/embedded_shaders.h"
#include "vk/pipeline.h"
#include "vk/shader_bindings.h"

#include <algorithm>
#include <map>

using namespace ssgi;

namespace {

const vk::EmbeddedShader& embedded(const std::string& name) {
    const auto& all = vk::embeddedShaders();
    auto found =
        std::find_if(all.begin(), all.end(), [&](const auto& s) { return name == s.name; });
    if (found == all.end()) throw std::runtime_error("no shader " + name);
    return *found;
}

constexpr VkDescriptorType kUniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;

// indirect_reconstruct.comp: the frame's uniforms, seven sampler2Ds, two rgba16f image2Ds and one
// more sampler2D.
const std::vector<vk::LayoutBinding> kReconstruct = {
    {kUniform, "FrameBlock"},
    {kSampled, "gbufferViewDepth"},
    {kSampled, "gbufferNormal"},
    {kSampled, "historyViewDepth"},
    {kSampled, "reprojection"},
    {kSampled, "historyCount"},
    {kSampled, "estimates"},
    {kSampled, "directionals"},
    {kStorage, "filtered", false, VK_FORMAT_R16G16B16A16_SFLOAT},
    {kStorage, "filteredDirectional", false, VK_FORMAT_R16G16B16A16_SFLOAT},
    {kSampled, "historyValue"}};

} // namespace

// A failed call's message names its VkResult: the presentation codes by name, any other by its
// number (a swapchain that failed on an H200 under Xvfb said only "VkResult error").
TEST(VulkanResults, AreNamedOrNumbered) {
    EXPECT_STREQ(vk::resultName(VK_ERROR_OUT_OF_DATE_KHR), "VK_ERROR_OUT_OF_DATE_KHR");
    EXPECT_STREQ(vk::resultName(VK_ERROR_SURFACE_LOST_KHR), "VK_ERROR_SURFACE_LOST_KHR");
    EXPECT_STREQ(vk::resultName(VK_ERROR_DEVICE_LOST), "VK_ERROR_DEVICE_LOST");
    EXPECT_STREQ(vk::resultName(VkResult(-1000255000)), "VkResult -1000255000");
}

TEST(ShaderBindings, ReflectTheShadersOwnDeclarations) {
    const vk::EmbeddedShader& s = embedded("indirect_reconstruct.comp");
    const auto bindings = vk::shaderBindings(s.code, s.bytes / 4, 0);
    ASSERT_EQ(bindings.size(), kReconstruct.size());
    for (uint32_t b = 0; b < kReconstruct.size(); ++b) {
        EXPECT_EQ(bindings.at(b).type, kReconstruct[b].type) << "binding " << b;
        EXPECT_EQ(bindings.at(b).name, kReconstruct[b].name) << "binding " << b;
    }
    EXPECT_TRUE(bindings.at(8).writable) << "filtered is writeonly, not readonly";
    EXPECT_EQ(bindings.at(8).format, VK_FORMAT_R16G16B16A16_SFLOAT) << "layout(rgba16f)";
    EXPECT_EQ(bindings.at(6).format, VK_FORMAT_UNDEFINED) << "a sampler2D has no format";
    // A storage image declared without a format (the temporal pass writes either history).
    const vk::EmbeddedShader& t = embedded("temporal.comp");
    for (const auto& [b, binding] : vk::shaderBindings(t.code, t.bytes / 4, 0))
        if (binding.name == "newValue0") {
            EXPECT_EQ(binding.format, VK_FORMAT_UNDEFINED);
        }
    EXPECT_TRUE(vk::shaderBindings(s.code, s.bytes / 4, 1).empty()) << "nothing in set 1";
    // A graphics shader with a texture in set 1: the G-buffer's fragment shader.
    const vk::EmbeddedShader& g = embedded("gbuffer.frag");
    EXPECT_FALSE(vk::shaderBindings(g.code, g.bytes / 4, 0).empty());
}

class PipelineTest : public test::VulkanTest {};

TEST_F(PipelineTest, TheShadersOwnLayoutIsAccepted) {
    vk::Pipeline p =
        vk::createComputePipeline(test::context(), "indirect_reconstruct.comp", kReconstruct, 80,
                                  {{{"INTERLEAVE", 4}, {"RADIUS", 8}}});
    EXPECT_NE(p.pipeline, VK_NULL_HANDLE);
    vk::destroyPipeline(test::context(), p);
}

TEST_F(PipelineTest, ALayoutThatDisagreesIsRefusedNamingShaderAndBinding) {
    auto refusal = [](std::vector<vk::LayoutBinding> layout) {
        try {
            vk::Pipeline p =
                vk::createComputePipeline(test::context(), "indirect_reconstruct.comp", layout, 80);
            vk::destroyPipeline(test::context(), p);
        } catch (const vk::VulkanError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    std::vector<vk::LayoutBinding> wrongType = kReconstruct;
    wrongType[6].type = kStorage; // the shader samples binding 6
    const std::string type = refusal(wrongType);
    EXPECT_NE(type.find("indirect_reconstruct.comp binding 6"), std::string::npos) << type;
    EXPECT_NE(type.find("sampled image"), std::string::npos) << type;

    std::vector<vk::LayoutBinding> missing(kReconstruct.begin(), kReconstruct.end() - 1);
    const std::string lacks = refusal(missing);
    EXPECT_NE(lacks.find("binding 10"), std::string::npos) << lacks;
    EXPECT_NE(lacks.find("lacks"), std::string::npos) << lacks;

    // A storage image the pass would take as read only (graph::Use::StorageRead) that the shader
    // may write: the graph would leave its writes out of the barriers.
    std::vector<vk::LayoutBinding> readOnly = kReconstruct;
    readOnly[8].readOnly = true;
    const std::string writable = refusal(readOnly);
    EXPECT_NE(writable.find("indirect_reconstruct.comp binding 8"), std::string::npos) << writable;
    EXPECT_NE(writable.find("not declared readonly"), std::string::npos) << writable;

    std::vector<vk::LayoutBinding> extra = kReconstruct;
    extra.push_back(kStorage);
    const std::string never = refusal(extra);
    EXPECT_NE(never.find("binding 11"), std::string::npos) << never;
    EXPECT_NE(never.find("never declares"), std::string::npos) << never;

    // A storage image of another format than the shader declares: its texels would be written
    // as another layout.
    std::vector<vk::LayoutBinding> format = kReconstruct;
    format[9].format = VK_FORMAT_R16G16_SFLOAT;
    const std::string formats = refusal(format);
    EXPECT_NE(formats.find("indirect_reconstruct.comp binding 9"), std::string::npos) << formats;
    EXPECT_NE(formats.find("declared as rgba16f"), std::string::npos) << formats;
    EXPECT_NE(formats.find("an image of rg16f"), std::string::npos) << formats;
}

// Two images swapped in a pass's list have the same type: only the names tell them apart, and the
// refusal names both.
TEST_F(PipelineTest, ABindingTheShaderNamesOtherwiseIsRefusedNamingBoth) {
    std::vector<vk::LayoutBinding> swapped = kReconstruct;
    std::swap(swapped[3], swapped[4]);
    std::string message = "accepted";
    try {
        vk::Pipeline p =
            vk::createComputePipeline(test::context(), "indirect_reconstruct.comp", swapped, 80);
        vk::destroyPipeline(test::context(), p);
    } catch (const vk::VulkanError& e) {
        message = e.what();
    }
    EXPECT_NE(message.find("indirect_reconstruct.comp binding 3"), std::string::npos) << message;
    EXPECT_NE(message.find("historyViewDepth"), std::string::npos) << message;
    EXPECT_NE(message.find("declares reprojection"), std::string::npos) << message;
}

// The specialization constants and the workgroup size are read from the SPIR-V, as the bindings
// are: a pass gives its constants by name, and the dispatch counts groups of the shader's size.
TEST(ShaderBindings, ReflectSpecializationConstantsAndWorkgroupSize) {
    const vk::EmbeddedShader& s = embedded("composite.comp");
    const std::map<std::string, uint32_t> constants = vk::shaderSpecConstants(s.code, s.bytes / 4);
    const std::map<std::string, uint32_t> expected = {{"HAS_CONTACT", 0},
                                                      {"TERM0_ROLE", 1},
                                                      {"TERM1_ROLE", 2},
                                                      {"TERM2_ROLE", 3},
                                                      {"TERM3_ROLE", 4}};
    EXPECT_EQ(constants, expected);
    const vk::WorkgroupSize group = vk::shaderWorkgroupSize(s.code, s.bytes / 4);
    EXPECT_EQ(group.x, 8u);
    EXPECT_EQ(group.y, 8u);
    const vk::EmbeddedShader& probe = embedded("probe_fill.comp");
    EXPECT_TRUE(vk::shaderSpecConstants(probe.code, probe.bytes / 4).empty());
}

TEST_F(PipelineTest, SpecializationConstantsAreGivenByTheShadersNames) {
    auto refusal = [](const vk::Specialization& spec) {
        try {
            vk::Pipeline p = vk::createComputePipeline(test::context(), "indirect_reconstruct.comp",
                                                       kReconstruct, 80, spec);
            vk::destroyPipeline(test::context(), p);
        } catch (const vk::VulkanError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    // In either order: each goes to the constant of its name.
    EXPECT_EQ(refusal({{{"RADIUS", 8}, {"INTERLEAVE", 4}}}), "accepted");
    const std::string unknown = refusal({{{"INTERLEAVE", 4}, {"RADIUS", 8}, {"TAPS", 9}}});
    EXPECT_NE(unknown.find("indirect_reconstruct.comp declares no specialization constant TAPS"),
              std::string::npos)
        << unknown;
    const std::string missing = refusal({{{"INTERLEAVE", 4}}});
    EXPECT_NE(missing.find("RADIUS, which the pass does not give"), std::string::npos) << missing;
}

// A depth-only pipeline (no fragment shader: the shadow map's opaque draws, scene_pass.cpp) is
// the vertex stage alone: its set 0 is what the vertex shader reads (the frame's uniforms), the
// texture only the fragment shader would read is refused as one it never declares, and its
// layout's stages (push constants' included) are the vertex stage's.
TEST_F(PipelineTest, ADepthOnlyPipelineIsTheVertexStageAlone) {
    vk::GraphicsPipelineDesc desc;
    desc.vertices = sceneVertexInput();
    desc.vertexShader = "shadow_map.vert";
    desc.depthFormat = VK_FORMAT_D32_SFLOAT;
    desc.bindings = {{kUniform, "FrameBlock"}};
    desc.pushConstantSize = sizeof(shader::DrawConstants);
    vk::Pipeline p = vk::createGraphicsPipeline(test::context(), desc);
    EXPECT_NE(p.pipeline, VK_NULL_HANDLE);
    EXPECT_EQ(p.stages, VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT));
    EXPECT_EQ(p.bindingCount, 1u);
    vk::destroyPipeline(test::context(), p);

    auto refusal = [](const vk::GraphicsPipelineDesc& d) {
        try {
            vk::Pipeline p = vk::createGraphicsPipeline(test::context(), d);
            vk::destroyPipeline(test::context(), p);
        } catch (const vk::VulkanError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    vk::GraphicsPipelineDesc texture = desc;
    texture.bindings.push_back({kSampled, "baseColorTexture"});
    const std::string never = refusal(texture);
    EXPECT_NE(never.find("binding 1"), std::string::npos) << never;
    EXPECT_NE(never.find("shadow_map.vert never declares"), std::string::npos) << never;
    vk::GraphicsPipelineDesc colour = desc;
    colour.colorFormats = {VK_FORMAT_R8G8B8A8_UNORM};
    const std::string targets = refusal(colour);
    EXPECT_NE(targets.find("colour targets need a fragment shader"), std::string::npos) << targets;
}
