// A compute pass declared once. The pass lists the images it binds, in the order of its shader's
// bindings, each with the name the shader gives it and how the pass uses it; its uniform buffers
// follow. From that one list come the pipeline's layout (binding 0 the frame's uniforms, then the
// images: a sampled use is a sampler2D, a storage use an image2D, then the buffers), the
// descriptors pushed each frame, and the graph's barriers. When the pipeline is made, the
// shader's own declarations (read from its SPIR-V) are held to the list, names included: a
// binding the shader calls otherwise, types that differ, or a count that differs is an error
// naming the shader, the binding and both names (vk/shader_bindings.h).
#pragma once

#include "graph/frame_graph.h"
#include "vk/pipeline.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ssgi {

class FrameBuild;
struct FrameState;

// One image a compute pass binds.
struct ShaderImage {
    std::string name;      // the shader's variable
    graph::ImageRef image; // the image behind it this frame
    // Sampled, StorageRead (imageLoad only), StorageWrite or StorageReadWrite.
    graph::Use use;
    VkSampler sampler = VK_NULL_HANDLE; // for a sampled use: the setup's nearest unless given
};

// One uniform buffer a compute pass binds, after its images (or, `storage`, a storage buffer:
// std430, which lays out scalars and arrays as C++ does).
struct ShaderBuffer {
    std::string name; // the shader's uniform or buffer block
    vk::Buffer buffer;
    bool storage = false;
};

struct ComputePassDesc {
    std::string name;   // the pass, as the graph, the profile and the debug labels name it
    std::string shader; // e.g. "ao.comp"
    std::vector<ShaderImage> images;
    std::vector<ShaderBuffer> uniforms;
    uint32_t pushSize = 0; // the shader's push-constant block, bytes
    vk::Specialization spec;
    // A second variant, for the frames where the pass's results start anew (its cache's history
    // restarts): ComputeRecorder::restarting dispatches it. A cached effect takes all of its
    // samples there and its share on the frames that continue (cache.h samplesPerFrame).
    std::optional<vk::Specialization> restartSpec;
};

// What a compute pass's record function gets: this frame's state, and dispatch(), which pushes
// the declared descriptors, then the constants, and dispatches enough of the shader's workgroups
// to cover width x height.
class ComputeRecorder {
public:
    ComputeRecorder(const FrameBuild& build, const graph::PassContext& pass,
                    const ComputePassDesc& desc, const vk::Pipeline& pipeline,
                    const vk::Pipeline& restartPipeline)
        : build_(build), pass_(pass), desc_(desc), pipeline_(pipeline),
          restartPipeline_(restartPipeline) {}
    const FrameState& frame() const { return pass_.frame; }
    // This recorder dispatching the pass's restart variant (ComputePassDesc::restartSpec; the
    // pass's own pipeline where it has none).
    ComputeRecorder restarting() const {
        return ComputeRecorder(build_, pass_, desc_, restartPipeline_, restartPipeline_);
    }
    template <typename T> void dispatch(uint32_t width, uint32_t height, const T& constants) const {
        dispatch(width, height, &constants, sizeof(T));
    }
    void dispatch(uint32_t width, uint32_t height) const { dispatch(width, height, nullptr, 0); }
    // As dispatch, the workgroup counts read by the device from `buffer` at `offset` (a
    // VkDispatchIndirectCommand written earlier in the frame; the caller records the barrier
    // that makes it visible to the indirect read).
    template <typename T>
    void dispatchIndirect(VkBuffer buffer, VkDeviceSize offset, const T& constants) const {
        dispatchIndirect(buffer, offset, &constants, sizeof(T));
    }

private:
    void dispatch(uint32_t width, uint32_t height, const void* constants, uint32_t size) const;
    void dispatchIndirect(VkBuffer buffer, VkDeviceSize offset, const void* constants,
                          uint32_t size) const;
    void pushDescriptors() const;
    const FrameBuild& build_;
    const graph::PassContext& pass_;
    const ComputePassDesc& desc_;
    const vk::Pipeline& pipeline_;
    const vk::Pipeline& restartPipeline_;
};

using ComputeRecordFn = std::function<void(const ComputeRecorder&)>;

// Makes the pipeline (checked against the shader as above) and adds the pass to the graph, its
// uses those of `desc.images`. `enabled` as FrameGraph::addPass.
void addComputePass(FrameBuild& build, ComputePassDesc desc, ComputeRecordFn record,
                    graph::EnabledFn enabled = {});

} // namespace ssgi
