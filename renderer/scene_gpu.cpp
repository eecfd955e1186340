#include "scene_gpu.h"

#include "shared.h"

#include <cstddef>
#include <stdexcept>

namespace ssgi {

vk::VertexInput sceneVertexInput() {
    return {sizeof(Vertex),
            {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
             {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
             {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
             {3, 0, VK_FORMAT_R16G16B16A16_UNORM, offsetof(Vertex, color)}}};
}

SceneGpu::SceneGpu(vk::Context& ctx, const Scene& scene) : ctx_(ctx), scene_(&scene) {
    for (const Instance& instance : scene.instances)
        transforms_.push_back(instance.transform);
    const uint32_t limit = ctx.properties.limits.maxImageDimension2D;
    for (size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        if (t.width > limit || t.height > limit)
            throw InputError(scene.sourcePath + ": texture " + std::to_string(i) + " '" + t.name +
                             "' is " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                             ", beyond this device's largest 2D image (" + std::to_string(limit) +
                             ")");
    }
    for (const Mesh& mesh : scene.meshes) {
        MeshBuffers b;
        // Meshes without indices (flat-shaded, one vertex per corner) draw their vertices in order.
        std::vector<uint32_t> sequential;
        if (mesh.indices.empty())
            for (uint32_t i = 0; i < mesh.vertices.size(); ++i)
                sequential.push_back(i);
        const std::vector<uint32_t>& indices = mesh.indices.empty() ? sequential : mesh.indices;
        if (!indices.empty()) {
            b.vertices = vk::createBufferWithData(ctx, mesh.vertices.data(),
                                                  mesh.vertices.size() * sizeof(Vertex),
                                                  VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
            b.indices =
                vk::createBufferWithData(ctx, indices.data(), indices.size() * sizeof(uint32_t),
                                         VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
            b.indexCount = uint32_t(indices.size());
        }
        meshes_.push_back(b);
    }
    for (size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        try {
            textures_.push_back(vk::createTexture(ctx, t.name, VK_FORMAT_R8G8B8A8_SRGB,
                                                  {t.width, t.height}, t.rgba.data(),
                                                  t.rgba.size()));
        } catch (const std::exception& error) {
            // A legal texture the memory left cannot hold: named, with what it needs (the
            // device's own out-of-memory code said neither). What was made is released, as
            // the destructor of an object never made would not.
            const std::string why = error.what();
            vkDeviceWaitIdle(ctx.device);
            for (MeshBuffers& m : meshes_) {
                vk::destroyBuffer(ctx, m.vertices);
                vk::destroyBuffer(ctx, m.indices);
            }
            for (vk::Image& made : textures_)
                vk::destroyImage(ctx, made);
            throw InputError(scene.sourcePath + ": texture " + std::to_string(i) +
                             (t.name.empty() ? "" : " '" + t.name + "'") + " (" +
                             std::to_string(t.width) + "x" + std::to_string(t.height) + ", " +
                             std::to_string((t.rgba.size() + (1 << 20) - 1) >> 20) +
                             " MiB, twice that while it is uploaded) does not fit in the memory "
                             "left: " +
                             why);
        }
    }
    const uint8_t white[4] = {255, 255, 255, 255};
    whiteTexture_ = vk::createTexture(ctx, "white", VK_FORMAT_R8G8B8A8_SRGB, {1, 1}, white, 4);
    auto address = [](TextureWrap wrap) {
        return wrap == TextureWrap::ClampToEdge      ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE
               : wrap == TextureWrap::MirroredRepeat ? VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT
                                                     : VK_SAMPLER_ADDRESS_MODE_REPEAT;
    };
    auto filter = [](bool nearest) { return nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; };
    // The untextured draws read the white texel through the default sampler.
    samplers_[TextureSampler{}] = VK_NULL_HANDLE;
    for (const Material& material : scene.materials)
        samplers_[material.baseColorSampler] = VK_NULL_HANDLE;
    for (auto& [key, sampler] : samplers_)
        sampler = vk::createSampler(ctx, filter(key.magnifyNearest), filter(key.minifyNearest),
                                    address(key.wrapU), address(key.wrapV));
}

SceneGpu::~SceneGpu() {
    vkDeviceWaitIdle(ctx_.device);
    for (MeshBuffers& m : meshes_) {
        vk::destroyBuffer(ctx_, m.vertices);
        vk::destroyBuffer(ctx_, m.indices);
    }
    for (vk::Image& t : textures_)
        vk::destroyImage(ctx_, t);
    vk::destroyImage(ctx_, whiteTexture_);
    for (auto& entry : samplers_)
        vkDestroySampler(ctx_.device, entry.second, nullptr);
}

void SceneGpu::rebind(const Scene& scene) {
    if (scene.meshes.size() != scene_->meshes.size() ||
        scene.materials.size() != scene_->materials.size() ||
        scene.textures.size() != scene_->textures.size() ||
        scene.instances.size() != scene_->instances.size())
        throw std::logic_error("SceneGpu::rebind: a scene of other meshes, materials, textures "
                               "or instances than the one on the device");
    scene_ = &scene;
}

void SceneGpu::draw(VkCommandBuffer cmd, const vk::Pipeline& opaque, const vk::Pipeline& masked,
                    VkBuffer frameUniforms, VkDeviceSize frameUniformsSize,
                    const std::function<void(vk::Descriptors&)>& extra,
                    const std::vector<bool>& only) const {
    VkPipeline bound = VK_NULL_HANDLE;
    for (size_t i = 0; i < scene_->instances.size(); ++i) {
        if (!only.empty() && !only[i]) continue;
        const Instance& instance = scene_->instances[i];
        const MeshBuffers& mesh = meshes_[instance.mesh];
        if (mesh.indexCount == 0) continue;
        const Material& material = scene_->materials[scene_->meshes[instance.mesh].material];
        const vk::Pipeline& pipeline = material.alphaMask ? masked : opaque;
        if (pipeline.pipeline != bound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.pipeline);
            bound = pipeline.pipeline;
        }
        const bool textured = material.baseColorTexture >= 0;
        shader::DrawConstants constants{};
        constants.model = transforms_[i];
        constants.baseColorFactor = material.baseColorFactor;
        constants.material = {textured ? 1.0f : 0.0f,
                              material.alphaMask ? material.alphaCutoff : 0.0f,
                              scene_->meshes[instance.mesh].vertexColors ? 1.0f : 0.0f, 0.0f};
        vk::Descriptors descriptors;
        descriptors.uniformBuffer(0, frameUniforms, frameUniformsSize);
        if (pipeline.bindingCount > 1) {
            descriptors.sampledImage(
                1, textured ? textures_[material.baseColorTexture].view : whiteTexture_.view,
                samplers_.at(textured ? material.baseColorSampler : TextureSampler{}));
            if (extra) extra(descriptors);
        }
        descriptors.push(ctx_, cmd, pipeline);
        vkCmdPushConstants(cmd, pipeline.layout, pipeline.stages, 0, sizeof(constants), &constants);
        VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &mesh.vertices.buffer, &offset);
        vkCmdBindIndexBuffer(cmd, mesh.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, mesh.indexCount, 1, 0, 0, 0);
    }
}

} // namespace ssgi
