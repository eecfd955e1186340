// The scene on the device: one vertex and index buffer per mesh, the base-colour textures, and
// the draw list (one draw per instance) shared by every raster pass.
#pragma once

#include "scene/scene.h"
#include "vk/pipeline.h"
#include "vk/resources.h"

#include <functional>
#include <map>
#include <vector>

namespace ssgi {

// The layout of the scene's vertex buffers (ssgi::Vertex: position, normal, uv, colour at
// locations 0, 1, 2, 3), for every pipeline that draws them.
vk::VertexInput sceneVertexInput();

class SceneGpu {
public:
    SceneGpu(vk::Context& ctx, const Scene& scene);
    ~SceneGpu();
    SceneGpu(const SceneGpu&) = delete;
    SceneGpu& operator=(const SceneGpu&) = delete;

    // Draws every instance with `pipeline` (set 0: binding 0 = frame uniforms, binding 1 = the
    // draw's base-colour texture with its material's sampler, then whatever `extra` adds; push
    // constants = DrawConstants);
    // with `only` given, the instances it marks.
    void draw(VkCommandBuffer cmd, const vk::Pipeline& pipeline, VkBuffer frameUniforms,
              VkDeviceSize frameUniformsSize,
              const std::function<void(vk::Descriptors&)>& extra = {},
              const std::vector<bool>& only = {}) const {
        draw(cmd, pipeline, pipeline, frameUniforms, frameUniformsSize, extra, only);
    }
    // As above, the instances of opaque materials with `opaque` and the alpha-masked ones with
    // `masked`, in the instances' order. An `opaque` pipeline whose set 0 is binding 0 alone (a
    // depth-only one, no fragment shader: scene_pass.h) is given the frame uniforms alone.
    void draw(VkCommandBuffer cmd, const vk::Pipeline& opaque, const vk::Pipeline& masked,
              VkBuffer frameUniforms, VkDeviceSize frameUniformsSize,
              const std::function<void(vk::Descriptors&)>& extra = {},
              const std::vector<bool>& only = {}) const;
    // Places the instances (moving objects) for the draws recorded from now on.
    void setTransforms(const std::vector<glm::mat4>& transforms) { transforms_ = transforms; }
    // Draws `scene` from now on: a scene with the meshes, materials, textures and instances of
    // the one this was made from (a copy with other settings, light or camera), which the
    // device's copy goes on standing for. std::logic_error for one of other counts.
    void rebind(const Scene& scene);

private:
    struct MeshBuffers {
        vk::Buffer vertices, indices;
        uint32_t indexCount = 0;
    };
    vk::Context& ctx_;
    const Scene* scene_;
    std::vector<MeshBuffers> meshes_;
    std::vector<glm::mat4> transforms_; // per instance
    std::vector<vk::Image> textures_;
    vk::Image whiteTexture_;
    std::map<TextureSampler, VkSampler> samplers_; // one for each sampler the materials use
};

} // namespace ssgi
