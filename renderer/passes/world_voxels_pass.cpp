// world.voxel_clear + world.voxelize (indirect_method 3): the scene's voxel occupancy grid, the
// representation the world cache tests its VPLs' visibility in. It does not depend on the view:
// drawn on the first frame and again only after an object moved (FrameState::drawVoxels), the
// whole scene at once. The grid spans the scene's bounds (wherever its objects' paths take them)
// with cubic voxels, world_voxels along the longest side.
//   reads:  the scene's draws
//   writes: world.voxels (R32UI, one bit a voxel), world.voxel_blocks (one bit for each 4 x 4 x 4
//           voxels: world_voxels.glsl)
#include "frame_uniforms.h"
#include "passes/passes.h"

#include <algorithm>
#include <cmath>

namespace ssgi {

shader::WorldConstants worldGridConstants(const Scene& scene) {
    const Aabb& bounds = scene.bounds;
    const glm::dvec3 origin = gpuOrigin(bounds);
    const glm::vec3 lo = moved(bounds.min, origin);
    const glm::vec3 hi = moved(bounds.max, origin);
    const glm::vec3 extent = glm::max(hi - lo, glm::vec3(0.0f));
    const float longest = std::max({extent.x, extent.y, extent.z, 1e-30f});
    const int voxelsAlong = int(scene.settings.world_voxels);
    // A voxel more than the bounds on each side, so that no surface lies on the grid's edge.
    const float voxel = longest / float(voxelsAlong - 2);
    shader::WorldConstants c{};
    c.gridOrigin = glm::vec4(lo - glm::vec3(voxel), voxel);
    for (int axis = 0; axis < 3; ++axis)
        c.gridSize[axis] = std::clamp(int(std::ceil(extent[axis] / voxel)) + 2, 1, voxelsAlong);
    c.gridSize.w = (c.gridSize.x + 31) / 32;
    return c;
}

WorldGrid addWorldVoxelPasses(FrameBuild& build) {
    WorldGrid grid;
    grid.constants = worldGridConstants(build.scene);
    const glm::ivec4 size = grid.constants.gridSize;
    const VkExtent2D extent{uint32_t(size.w * size.z), uint32_t(size.y)};
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    grid.voxels = build.graph.createImage("world.voxels", VK_FORMAT_R32_UINT, extent, usage, true);
    // Its 4 x 4 x 4 blocks (world_voxels.glsl), laid out the same way.
    const glm::ivec3 blocks = (glm::ivec3(size) + 3) / 4;
    const VkExtent2D blockExtent{uint32_t((blocks.x + 31) / 32 * blocks.z), uint32_t(blocks.y)};
    grid.blocks =
        build.graph.createImage("world.voxel_blocks", VK_FORMAT_R32_UINT, blockExtent, usage, true);
    const graph::EnabledFn onVoxelFrames = [](const FrameState& frame) {
        return frame.drawVoxels;
    };
    using graph::Use;
    build.graph.addPass(
        "world.voxel_clear", graph::PassKind::Transfer,
        {{grid.voxels, Use::TransferDst}, {grid.blocks, Use::TransferDst}},
        [grid](const graph::PassContext& pc) {
            const VkClearColorValue zero{};
            const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            for (const graph::ImageRef& image : {grid.voxels, grid.blocks})
                vkCmdClearColorImage(pc.cmd, pc.image(image).image,
                                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
        },
        onVoxelFrames);

    // Two pixels a voxel along each of the view's axes: a triangle smaller than a voxel still
    // covers a pixel's centre more often.
    constexpr int kSupersample = 2;
    const vk::Buffer& uniforms = build.uniformBuffer(&grid.constants, sizeof(grid.constants));
    std::vector<vk::Pipeline> pipelines;
    for (int axis = 0; axis < 3; ++axis) {
        vk::GraphicsPipelineDesc desc;
        desc.vertices = sceneVertexInput();
        desc.vertexShader = "world_voxelize.vert";
        desc.fragmentShader = "world_voxelize.frag";
        desc.bindings = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, "FrameBlock"},
                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, "baseColorTexture"},
                         {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, "voxels", false, VK_FORMAT_R32_UINT},
                         {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, "WorldBlock"},
                         {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, "voxelBlocks", false,
                          VK_FORMAT_R32_UINT}};
        desc.pushConstantSize = sizeof(shader::DrawConstants);
        desc.vertexSpec = {{{"AXIS", axis}}};
        desc.fragmentSpec = {{{"AXIS", axis}, {"SUPERSAMPLE", kSupersample}}};
        pipelines.push_back(build.graphicsPipeline(desc));
    }
    build.graph.addPass(
        "world.voxelize", graph::PassKind::Graphics,
        {{grid.voxels, Use::StorageReadWrite}, {grid.blocks, Use::StorageReadWrite}},
        [&build, grid, size, pipelines, &uniforms](const graph::PassContext& pc) {
            for (int axis = 0; axis < 3; ++axis) {
                // The view's axes are the two after `axis` (world_voxelize.vert).
                const VkExtent2D view{uint32_t(size[(axis + 1) % 3] * kSupersample),
                                      uint32_t(size[(axis + 2) % 3] * kSupersample)};
                VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                info.renderArea = {{0, 0}, view};
                info.layerCount = 1;
                vkCmdBeginRendering(pc.cmd, &info);
                VkViewport viewport{0, 0, float(view.width), float(view.height), 0, 1};
                VkRect2D scissor{{0, 0}, view};
                vkCmdSetViewport(pc.cmd, 0, 1, &viewport);
                vkCmdSetScissor(pc.cmd, 0, 1, &scissor);
                const VkImageView voxels = pc.image(grid.voxels).view;
                const VkImageView blocks = pc.image(grid.blocks).view;
                build.sceneGpu.draw(pc.cmd, pipelines[size_t(axis)], build.frameUniforms.buffer,
                                    build.frameUniforms.size, [&](vk::Descriptors& d) {
                                        d.storageImage(2, voxels);
                                        d.uniformBuffer(3, uniforms.buffer, uniforms.size);
                                        d.storageImage(4, blocks);
                                    });
                vkCmdEndRendering(pc.cmd);
            }
        },
        onVoxelFrames);
    return grid;
}

} // namespace ssgi
