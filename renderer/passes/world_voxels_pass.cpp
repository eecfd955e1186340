// world.voxel_clear + world.voxelize + world.voxel_distance_x, _y, _z (indirect_method 3): the
// scene's voxel occupancy grid, the representation the world cache tests its VPLs' visibility
// in. It does not depend on the view: the whole scene is drawn into it on the first frame and
// again only after the light or an object moved (FrameState::drawVoxels). The grid lies around
// the scene's geometry inside the light's frustum (world_grid.h), world_voxels cubic voxels
// along its longest side.
//   reads:  the scene's draws
//   writes: world.voxels (R32UI, one bit a voxel, 4 x 4 x 4 to two texels), world.voxel_distance
//           (R8UI, each block's distance to the nearest occupied one; it and
//           world.voxel_distance_xy hold the passes' partial distances between them:
//           world_voxels.glsl)
#include "passes/passes.h"

#include <algorithm>
#include <cmath>

namespace ssgi {

WorldGrid addWorldVoxelPasses(FrameBuild& build) {
    WorldGrid grid;
    // Images for the largest grid, world_voxels a side: the grid's place and size are the
    // frame's (FrameUniforms.worldGridOrigin, worldGridSize; world_grid.h), which change when
    // the light or an object moves.
    const int side = int(build.settings.world_voxels);
    const int blocks = (side + WORLD_BLOCK - 1) / WORLD_BLOCK;
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    // Two texels a block (world_voxels.glsl).
    const VkExtent2D extent{uint32_t(2 * blocks * blocks), uint32_t(blocks)};
    const uint32_t limit = build.ctx.properties.limits.maxImageDimension2D;
    if (extent.width > limit) {
        const int most = int(std::sqrt(double(limit / 2))) * WORLD_BLOCK;
        throw InputError("world_voxels " + std::to_string(side) + " needs a " +
                         std::to_string(extent.width) + "x" + std::to_string(extent.height) +
                         " image of the voxel grid, beyond this device's largest 2D image (" +
                         std::to_string(limit) + "): at most " + std::to_string(most) + " here");
    }
    grid.voxels = build.graph.createImage("world.voxels", VK_FORMAT_R32_UINT, extent, usage, true);
    const graph::EnabledFn onVoxelFrames = [](const FrameState& frame) { return frame.drawVoxels; };
    using graph::Use;
    addClearPass(build, "world.voxel_clear", {grid.voxels}, onVoxelFrames);

    // Two pixels a voxel along each of the view's axes: a triangle smaller than a voxel still
    // covers a pixel's centre more often.
    constexpr int kSupersample = 2;
    std::vector<vk::Pipeline> pipelines;
    for (int axis = 0; axis < 3; ++axis) {
        vk::GraphicsPipelineDesc desc;
        desc.vertices = sceneVertexInput();
        desc.vertexShader = "world_voxelize.vert";
        desc.fragmentShader = "world_voxelize.frag";
        desc.bindings = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, "FrameBlock"},
                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, "baseColorTexture"},
                         {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, "voxels", false, VK_FORMAT_R32_UINT}};
        desc.pushConstantSize = sizeof(shader::DrawConstants);
        desc.vertexSpec = {{{"AXIS", axis}}};
        desc.fragmentSpec = {{{"AXIS", axis}, {"SUPERSAMPLE", kSupersample}}};
        pipelines.push_back(build.graphicsPipeline(desc));
    }
    build.graph.addPass(
        "world.voxelize", graph::PassKind::Graphics, {{grid.voxels, Use::StorageReadWrite}},
        [&build, grid, side, pipelines](const graph::PassContext& pc) {
            // Each axis's view holds the largest grid (world_voxelize.vert).
            const VkExtent2D view{uint32_t(side * kSupersample), uint32_t(side * kSupersample)};
            for (int axis = 0; axis < 3; ++axis) {
                VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
                info.renderArea = {{0, 0}, view};
                info.layerCount = 1;
                vkCmdBeginRendering(pc.cmd, &info);
                VkViewport viewport{0, 0, float(view.width), float(view.height), 0, 1};
                VkRect2D scissor{{0, 0}, view};
                vkCmdSetViewport(pc.cmd, 0, 1, &viewport);
                vkCmdSetScissor(pc.cmd, 0, 1, &scissor);
                const VkImageView voxels = pc.image(grid.voxels).view;
                build.sceneGpu.draw(pc.cmd, pipelines[size_t(axis)], build.frameUniforms.buffer,
                                    build.frameUniforms.size,
                                    [&](vk::Descriptors& d) { d.storageImage(2, voxels); });
                vkCmdEndRendering(pc.cmd);
            }
        },
        onVoxelFrames);

    // Each block's distance to the nearest occupied one, an axis a pass: x from the voxels
    // into the distance image (the distance along the row), y from it into the xy image, z from
    // that back into the distance image, which then holds the whole distance.
    const VkExtent2D distanceExtent{uint32_t(blocks * blocks), uint32_t(blocks)};
    const graph::ImageRef distance = build.graph.createImage(
        "world.voxel_distance", VK_FORMAT_R8_UINT, distanceExtent, usage, true);
    const graph::ImageRef afterY = build.graph.createImage(
        "world.voxel_distance_xy", VK_FORMAT_R8_UINT, distanceExtent, usage, true);
    const graph::ImageRef sources[3] = {grid.voxels, distance, afterY};
    const graph::ImageRef targets[3] = {distance, afterY, distance};
    for (int axis = 0; axis < 3; ++axis) {
        ComputePassDesc pass{std::string("world.voxel_distance_") + "xyz"[axis],
                             "world_voxel_distance.comp"};
        pass.images = {{"source", sources[axis], Use::Sampled},
                       {"distanceOut", targets[axis], Use::StorageWrite}};
        pass.spec = {{{"AXIS", axis}}};
        addComputePass(
            build, std::move(pass),
            [blocks](const ComputeRecorder& r) {
                r.dispatch(uint32_t(blocks), uint32_t(blocks * blocks));
            },
            onVoxelFrames);
    }
    grid.distance = distance;
    return grid;
}

} // namespace ssgi
