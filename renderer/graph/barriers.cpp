#include "graph/barriers.h"

namespace ssgi::graph {

UseInfo useInfo(Use use, PassKind kind) {
    const VkPipelineStageFlags2 shaderStage = kind == PassKind::Graphics
                                                  ? VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT
                                                  : VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    switch (use) {
    case Use::Sampled:
        return {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, shaderStage,
                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, false};
    case Use::StorageRead:
        return {VK_IMAGE_LAYOUT_GENERAL, shaderStage, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, false};
    case Use::StorageWrite:
        return {VK_IMAGE_LAYOUT_GENERAL, shaderStage, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, true};
    case Use::StorageReadWrite:
        return {VK_IMAGE_LAYOUT_GENERAL, shaderStage,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, true};
    case Use::ColorAttachment:
        return {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                true};
    case Use::DepthAttachment:
        return {VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                    VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                true};
    case Use::TransferSrc:
        return {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_TRANSFER_READ_BIT, false};
    case Use::TransferDst:
        return {VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_TRANSFER_WRITE_BIT, true};
    }
    return {};
}

std::optional<VkImageMemoryBarrier2> transition(ImageState& state, Use use, PassKind kind,
                                                bool discard, VkImage image,
                                                VkImageAspectFlags aspect) {
    const UseInfo next = useInfo(use, kind);
    const VkImageLayout oldLayout = discard ? VK_IMAGE_LAYOUT_UNDEFINED : state.layout;
    const bool layoutChange = oldLayout != next.layout;

    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.oldLayout = oldLayout;
    b.newLayout = next.layout;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, 0, 1, 0, 1};
    b.dstStageMask = next.stages;
    b.dstAccessMask = next.access;

    if (next.writes || layoutChange) {
        // A write (or a layout transition, which is a write) must wait for the last write and for
        // every read since, and make the last write available.
        b.srcStageMask = state.writeStages | state.readStages;
        b.srcAccessMask = state.writeAccess;
        state.layout = next.layout;
        if (next.writes) {
            state.writeStages = next.stages;
            state.writeAccess =
                next.access &
                (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
            state.readStages = 0;
            state.readAccess = 0;
        } else {
            // The layout transition is a write that completes before this reader's stages; later
            // readers in other stages chain on those stages (nothing more to make available).
            state.writeStages = next.stages;
            state.writeAccess = VK_ACCESS_2_NONE;
            state.readStages = next.stages;
            state.readAccess = next.access;
        }
        return b;
    }

    // A read in the same layout: needs a barrier only if the last write has not yet been made
    // visible to this stage and access.
    const bool seen = (state.readStages & next.stages) == next.stages &&
                      (state.readAccess & next.access) == next.access;
    if (state.writeStages == 0 || seen) {
        state.readStages |= next.stages;
        state.readAccess |= next.access;
        return std::nullopt;
    }
    b.srcStageMask = state.writeStages;
    b.srcAccessMask = state.writeAccess;
    state.readStages |= next.stages;
    state.readAccess |= next.access;
    return b;
}

} // namespace ssgi::graph
