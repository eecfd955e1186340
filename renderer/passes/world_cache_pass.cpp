// world.clear, world.insert, world.schedule, world.sky_visibility, world.gather, world.lookup,
// world.upsample, world.lookup_edges (indirect_method 3): the bounce held in world space. A hash
// table of cells (world_cache.glsl), each the irradiance at one surface point gathered from the
// RSM's VPLs with their visibility through the voxel grid (world_voxels_pass.cpp), which does not
// depend on the view: a moving camera looks the cells up and fills only the new ones. The table
// persists from frame to frame; without the cache it is cleared every frame and every cell
// filled at once. With the sky's maps (skyInWorldCache), a cell holds the sky's visibility at its
// point too, computed once when it starts (world_sky_visibility.comp), and the lookup writes it
// beside the bounce, in place of the per-pixel sky_visibility pass. With world_half_res, the
// lookup runs at the top-left pixel of every 2x2 block, world.upsample brings the bounce to full
// resolution, and world.lookup_edges looks it up at the pixels that have no sample on their
// surface.
//   reads:  gbuffer.view_depth, .normal, indirect.vpl_list (the flux's pool), the VPL map
//           (indirect.vpl_position, .vpl_normal, .vpl_flux), world.voxels, .voxel_distance,
//           sky.maps (with the sky)
//   writes: world.keys, .irradiance, .points, .used, .directions, .owner, .sky (the table),
//           world.stats (its counters), world.gather_list (the cells that gather this frame),
//           world.indirect (the bounce, irradiance / pi, RGBA16F: the composite's "indirect"),
//           world.sky_visibility (with the sky: the composite's "sky-visibility"),
//           world.indirect_half, world.sky_visibility_half and world.edge_list (world_half_res:
//           both at every other pixel, and the pixels looked up alone)
#include "passes/passes.h"
#include "passes/views.h"

#include <algorithm>
#include <cmath>

namespace ssgi {

int worldTableBits(const Settings& settings, VkExtent2D size) {
    if (settings.world_table_bits != 0) return int(settings.world_table_bits);
    // Half the image's pixels: a still view's cells are a tenth to a twentieth of them, and a
    // moving one keeps those it left for world_lifetime frames. At most 2^18 (16 MiB for the
    // table's images), so that 1920x1080 holds within its memory budget.
    const double half = 0.5 * double(size.width) * double(size.height);
    return std::clamp(int(std::ceil(std::log2(std::max(half, 1.0)))), 14, 18);
}

WorldLookups addWorldCachePasses(FrameBuild& build, const GBufferAndRsm& in, const FluxVpls& vpls,
                                 const WorldGrid& grid, const SkyMaps* sky) {
    const Settings& settings = build.settings;
    const int bits = worldTableBits(settings, build.size);
    // Powers of two both ways: world_cache.glsl indexes the table with masks and shifts.
    const VkExtent2D table{1u << (bits - bits / 2), 1u << (bits / 2)};
    shader::WorldConstants base{};
    const uint32_t vplMapSide =
        (build.rsmSize.width + uint32_t(settings.indirect_vpl_cluster) - 1) /
        uint32_t(settings.indirect_vpl_cluster);
    base.cells =
        glm::vec4(float(settings.world_cell_angle), settings.world_level_reuse ? 1.0f : 0.0f,
                  float(settings.world_frames), float(settings.world_new_cell_frames));
    base.table = glm::ivec4(int(table.width), int(table.width * table.height),
                            int(settings.world_lifetime), 0);
    const int pool = int(std::max(settings.indirect_flux_pool, settings.indirect_flux_vpls));
    base.work = glm::ivec4(int(settings.world_vpls), int(settings.world_cells_per_frame), pool,
                           WORLD_VIEW_LIGHT);
    base.change = glm::vec4(0.0f, 0.0f, 0.0f, float(vplMapSide));
    // This frame's: what changed, and what the lookup shows.
    const size_t cellsView = size_t(findView("world-cells") - kViews);
    const size_t ageView = size_t(findView("world-age") - kViews);
    auto constants = [base, cellsView, ageView](const FrameState& frame) {
        shader::WorldConstants c = base;
        c.change.y = frame.lightMoved ? 1.0f : 0.0f;
        c.change.z = frame.objectsMoved ? 1.0f : 0.0f;
        const size_t view = size_t(frame.view);
        c.work.w = view == cellsView ? WORLD_VIEW_CELLS
                   : view == ageView ? WORLD_VIEW_AGE
                                     : WORLD_VIEW_LIGHT;
        return c;
    };

    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    auto tableImage = [&](const char* name, VkFormat format) {
        return build.graph.createImage(name, format, table, usage, true);
    };
    const graph::ImageRef keys = tableImage("world.keys", VK_FORMAT_R32_UINT);
    const graph::ImageRef irradiance =
        tableImage("world.irradiance", VK_FORMAT_R32G32B32A32_SFLOAT);
    const graph::ImageRef points = tableImage("world.points", VK_FORMAT_R32G32B32A32_SFLOAT);
    const graph::ImageRef used = tableImage("world.used", VK_FORMAT_R32_UINT);
    const graph::ImageRef directions =
        tableImage("world.directions", VK_FORMAT_R32G32B32A32_SFLOAT);
    const graph::ImageRef owner = tableImage("world.owner", VK_FORMAT_R32_UINT);
    // The sky's visibility at each cell's point (rgb; a 1 once computed), with the sky.
    const graph::ImageRef skyTable =
        sky ? tableImage("world.sky", VK_FORMAT_R16G16B16A16_SFLOAT) : graph::ImageRef{};
    const graph::ImageRef stats =
        build.graph.createImage("world.stats", VK_FORMAT_R32_UINT, {WORLD_STATS, 3}, usage, true);
    const graph::ImageRef indirect =
        build.graph.createImage("world.indirect", VK_FORMAT_R16G16B16A16_SFLOAT, build.size, usage);
    // Where pixels look up: every pixel, or the top-left one of every 2x2 block.
    const bool halfRes = settings.world_half_res;
    const VkExtent2D screen = build.size;
    const VkExtent2D lookupSize =
        halfRes ? VkExtent2D{(screen.width + 1) / 2, (screen.height + 1) / 2} : screen;
    const int withSky = sky ? 1 : 0;
    // Without the sky, the shaders' sky images (never read or written: SKY 0) are bound to the
    // bounce's, used alike.
    const graph::ImageRef skyVisibility =
        sky ? build.graph.createImage("world.sky_visibility", VK_FORMAT_R16G16B16A16_SFLOAT, screen,
                                      usage)
            : indirect;

    using graph::Use;
    // Empty keys are zeros, and so are the counters; the cells' values and points too, so that
    // every texel of the table holds a number (an entry's are written before they are read).
    std::vector<graph::ImageRef> cleared = {keys,   used,       stats, irradiance,
                                            points, directions, owner};
    if (sky) cleared.push_back(skyTable);
    addClearPass(build, "world.clear", cleared,
                 [](const FrameState& frame) { return frame.clearWorldCache; });

    ComputePassDesc insert{"world.insert", "world_insert.comp"};
    insert.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                     {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                     {"worldKeys", keys, Use::StorageReadWrite},
                     {"worldIrradiance", irradiance, Use::StorageWrite},
                     {"worldOwner", owner, Use::StorageReadWrite},
                     {"worldUsed", used, Use::StorageReadWrite},
                     {"worldStats", stats, Use::StorageReadWrite},
                     {"worldDirections", directions, Use::StorageWrite}};
    insert.pushSize = sizeof(shader::WorldConstants);
    addComputePass(build, std::move(insert), [screen, constants](const ComputeRecorder& r) {
        r.dispatch(screen.width, screen.height, constants(r.frame()));
    });

    // The cells that gather this frame, entry + (frames << 22) (world_schedule.comp).
    const graph::ImageRef list =
        build.graph.createImage("world.gather_list", VK_FORMAT_R32_UINT, table, usage);
    ComputePassDesc schedule{"world.schedule", "world_schedule.comp"};
    schedule.images = {{"worldKeys", keys, Use::StorageReadWrite},
                       {"worldIrradiance", irradiance, Use::StorageReadWrite},
                       {"worldPoints", points, Use::StorageReadWrite},
                       {"worldUsed", used, Use::Sampled},
                       {"worldStats", stats, Use::StorageReadWrite},
                       {"gatherList", list, Use::StorageWrite},
                       {"worldOwner", owner, Use::StorageReadWrite},
                       {"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                       {"gbufferNormal", in.gbuffer.normal, Use::Sampled}};
    schedule.pushSize = sizeof(shader::WorldConstants);
    addComputePass(build, std::move(schedule), [table, constants](const ComputeRecorder& r) {
        r.dispatch(table.width, table.height, constants(r.frame()));
    });

    // The workgroups of the passes dispatched indirectly, as the passes before them counted them
    // in world.stats, copied to the buffer the indirect dispatch reads: a command for each of
    // them (0 world.gather, 1 world.lookup_edges) and each row of counters (frame parity).
    const vk::Buffer& dispatchSize =
        build.deviceBuffer(4 * sizeof(VkDispatchIndirectCommand),
                           VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    const VkBuffer sizes = dispatchSize.buffer;
    auto commandOffset = [](const FrameState& frame, uint32_t command) {
        return VkDeviceSize(2 * command + (frame.patternFrame & 1u)) *
               sizeof(VkDispatchIndirectCommand);
    };
    auto addDispatchSizePass = [&build, stats, sizes,
                                commandOffset](const char* name, uint32_t command, int32_t column) {
        build.graph.addPass(
            name, graph::PassKind::Transfer, {{stats, Use::TransferSrc}},
            [stats, sizes, commandOffset, command, column](const graph::PassContext& pc) {
                // After last frame's indirect reads of the buffer.
                vk::bufferBarrier(pc.cmd, sizes, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                                  VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
                                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
                VkBufferImageCopy region{};
                region.bufferOffset = commandOffset(pc.frame, command);
                region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.imageOffset = {column, int32_t(pc.frame.patternFrame & 1u), 0};
                region.imageExtent = {3, 1, 1};
                vkCmdCopyImageToBuffer(pc.cmd, pc.image(stats).image,
                                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, sizes, 1, &region);
                // Before the indirect read of it.
                vk::bufferBarrier(
                    pc.cmd, sizes, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
            });
    };
    addDispatchSizePass("world.dispatch_size", 0, WORLD_STAT_GROUPS);

    if (sky) {
        // Before the gather, while a starting cell's samples still read 0.
        shader::WorldSky skyView{sky->view, glm::vec4(sky->aoReach, sky->normalOffset, 0.0f, 0.0f)};
        ComputePassDesc skyPass{"world.sky_visibility", "world_sky_visibility.comp"};
        skyPass.images = {{"gatherList", list, Use::Sampled},
                          {"worldStats", stats, Use::StorageRead},
                          {"worldIrradiance", irradiance, Use::Sampled},
                          {"worldPoints", points, Use::Sampled},
                          {"skyMaps", sky->atlas, Use::Sampled},
                          {"worldSky", skyTable, Use::StorageWrite}};
        skyPass.uniforms = {{"TrianglesBlock", sky->exactTriangles},
                            {"SkyBlock", build.uniformBuffer(&skyView, sizeof(skyView))}};
        skyPass.pushSize = sizeof(shader::WorldConstants);
        addComputePass(
            build, std::move(skyPass), [sizes, constants, commandOffset](const ComputeRecorder& r) {
                r.dispatchIndirect(sizes, commandOffset(r.frame(), 0), constants(r.frame()));
            });
    }

    ComputePassDesc gather{"world.gather", "world_gather.comp"};
    gather.images = {{"voxels", grid.voxels, Use::Sampled},
                     {"voxelDistance", grid.distance, Use::Sampled},
                     {"vplList", vpls.list, Use::Sampled},
                     {"worldIrradiance", irradiance, Use::StorageReadWrite},
                     {"worldPoints", points, Use::Sampled},
                     {"worldStats", stats, Use::StorageReadWrite},
                     {"gatherList", list, Use::Sampled},
                     {"worldKeys", keys, Use::Sampled},
                     {"vplPosition", vpls.position, Use::Sampled},
                     {"vplNormal", vpls.normal, Use::Sampled},
                     {"vplFlux", vpls.flux, Use::Sampled},
                     {"worldDirections", directions, Use::StorageReadWrite}};
    gather.pushSize = sizeof(shader::WorldConstants);
    gather.spec = {{{"POOL", pool}}};
    addComputePass(build, std::move(gather),
                   [sizes, constants, commandOffset](const ComputeRecorder& r) {
                       r.dispatchIndirect(sizes, commandOffset(r.frame(), 0), constants(r.frame()));
                   });

    const graph::ImageRef looked =
        halfRes ? build.graph.createImage("world.indirect_half", VK_FORMAT_R16G16B16A16_SFLOAT,
                                          lookupSize, usage)
                : indirect;
    const graph::ImageRef skyLooked =
        halfRes && sky ? build.graph.createImage("world.sky_visibility_half",
                                                 VK_FORMAT_R16G16B16A16_SFLOAT, lookupSize, usage)
        : halfRes      ? looked
                       : skyVisibility;
    // What world_lookup.glsl reads: the G-buffer and the table, bound first by both passes that
    // look up.
    const std::vector<ShaderImage> lookupReads = {
        {"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
        {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
        {"worldKeys", keys, Use::Sampled},
        {"worldIrradiance", irradiance, Use::Sampled},
        {"worldUsed", used, Use::Sampled},
        {"worldPoints", points, Use::Sampled},
        {"worldDirections", directions, Use::Sampled},
        {"worldSky", sky ? skyTable : irradiance, Use::Sampled}};
    ComputePassDesc lookup{"world.lookup", "world_lookup.comp", lookupReads};
    lookup.images.push_back({"indirectImage", looked, Use::StorageWrite});
    lookup.images.push_back({"skyImage", skyLooked, Use::StorageWrite});
    lookup.pushSize = sizeof(shader::WorldConstants);
    lookup.spec = {{{"SCALE", halfRes ? 2 : 1}, {"SKY", withSky}}};
    addComputePass(build, std::move(lookup), [lookupSize, constants](const ComputeRecorder& r) {
        r.dispatch(lookupSize.width, lookupSize.height, constants(r.frame()));
    });
    if (halfRes) {
        // The pixels world.upsample leaves to world.lookup_edges, their indices in the image.
        const graph::ImageRef edges =
            build.graph.createImage("world.edge_list", VK_FORMAT_R32_UINT, screen, usage);
        ComputePassDesc upsample{"world.upsample", "world_upsample.comp"};
        upsample.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                           {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                           {"halfIndirect", looked, Use::Sampled},
                           {"indirectImage", indirect, Use::StorageWrite},
                           {"worldStats", stats, Use::StorageReadWrite},
                           {"edgeList", edges, Use::StorageWrite},
                           {"halfSky", skyLooked, Use::Sampled},
                           {"skyImage", skyVisibility, Use::StorageWrite}};
        upsample.pushSize = sizeof(shader::WorldConstants);
        upsample.spec = {{{"SKY", withSky}}};
        addComputePass(build, std::move(upsample), [screen, constants](const ComputeRecorder& r) {
            r.dispatch(screen.width, screen.height, constants(r.frame()));
        });
        addDispatchSizePass("world.edge_dispatch_size", 1, WORLD_STAT_EDGE_GROUPS);
        ComputePassDesc edgeLookup{"world.lookup_edges", "world_lookup_edges.comp", lookupReads};
        edgeLookup.images.push_back({"worldStats", stats, Use::Sampled});
        edgeLookup.images.push_back({"edgeList", edges, Use::Sampled});
        edgeLookup.images.push_back({"indirectImage", indirect, Use::StorageReadWrite});
        edgeLookup.images.push_back({"skyImage", skyVisibility, Use::StorageReadWrite});
        edgeLookup.pushSize = sizeof(shader::WorldConstants);
        edgeLookup.spec = {{{"SKY", withSky}}};
        addComputePass(build, std::move(edgeLookup),
                       [sizes, constants, commandOffset](const ComputeRecorder& r) {
                           r.dispatchIndirect(sizes, commandOffset(r.frame(), 1),
                                              constants(r.frame()));
                       });
    }
    return {indirect, sky ? skyVisibility : graph::ImageRef{}};
}

} // namespace ssgi
