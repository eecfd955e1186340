// How a declared image use becomes a synchronization2 barrier. Pure functions over a tracked
// per-image state, so the rules are testable on the CPU without a device.
#pragma once

#include <vulkan/vulkan.h>

#include <optional>

namespace ssgi::graph {

enum class PassKind { Graphics, Compute, Transfer };

enum class Use {
    Sampled,          // texture() in a shader
    StorageRead,      // imageLoad only, from an image2D the shader declares readonly
    StorageWrite,     // imageStore, previous contents irrelevant to this pass
    StorageReadWrite, // imageLoad and imageStore
    ColorAttachment,
    DepthAttachment,
    TransferSrc,
    TransferDst, // copies and clears into the image
};

// What a use means to the device: the layout it needs, the stages and accesses it performs.
struct UseInfo {
    VkImageLayout layout;
    VkPipelineStageFlags2 stages;
    VkAccessFlags2 access;
    bool writes;
};
UseInfo useInfo(Use use, PassKind kind);

// What has happened to an image since its last write: that write, and the reads after it which
// have already been made to see it.
struct ImageState {
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 writeStages = 0;
    VkAccessFlags2 writeAccess = 0;
    VkPipelineStageFlags2 readStages = 0; // stages that read since the last write
    VkAccessFlags2 readAccess = 0;        // accesses already made visible since the last write
};

// Returns the barrier needed before `use` (or nothing when none is needed) and updates `state`.
// `discard` says the previous contents are not needed (transient images at their first use in a
// frame): the old layout becomes UNDEFINED, but the execution dependency on earlier uses stays,
// since the memory is still being reused.
std::optional<VkImageMemoryBarrier2> transition(ImageState& state, Use use, PassKind kind,
                                                bool discard, VkImage image,
                                                VkImageAspectFlags aspect);

} // namespace ssgi::graph
