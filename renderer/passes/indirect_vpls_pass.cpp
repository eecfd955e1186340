// indirect.flux + indirect.vpls (indirect_methods 2 and 3): the VPLs of the importance gather
// and of the world cache's cells. The RSM
// clustered into a coarser map of VPLs, and a list of VPLs drawn this frame in proportion to
// their flux, through a pyramid of its luminance (indirect_vpls.comp).
//   reads:  rsm.vpls
//   writes: indirect.vpl_position, .vpl_normal, .vpl_flux (the VPL map, RGBA32F, the RSM's
//           side / indirect_vpl_cluster), indirect.flux_pyramid (R32F, the luminance's sums),
//           indirect.vpl_list (RGBA32F, indirect_flux_pool + 1 columns, 3 rows)
#include "passes/passes.h"

#include <algorithm>

namespace ssgi {

FluxVpls addFluxVplPasses(FrameBuild& build, const GBufferAndRsm& in, bool moving) {
    const Settings& settings = build.settings;
    const uint32_t mapSize = build.rsmSize.width;
    const uint32_t clusterSide = uint32_t(settings.indirect_vpl_cluster);
    const uint32_t vplMapSize = (mapSize + clusterSide - 1) / clusterSide;
    uint32_t padded = 8, levels = 3;
    while (padded < vplMapSize) {
        padded *= 2;
        ++levels;
    }
    const int count = int(std::max(settings.indirect_flux_pool, settings.indirect_flux_vpls));
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    // With the cache on, the VPL map is made again only when the RSM is drawn again (the light
    // moved), so it and the pyramid's levels over it persist; the list is drawn every frame.
    const bool persistent = settings.cache;
    auto vplImage = [&](const char* name) {
        return build.graph.createImage(name, VK_FORMAT_R32G32B32A32_SFLOAT,
                                       {vplMapSize, vplMapSize}, usage, persistent);
    };
    FluxVpls out;
    out.position = vplImage("indirect.vpl_position");
    out.normal = vplImage("indirect.vpl_normal");
    out.flux = vplImage("indirect.vpl_flux");
    const graph::ImageRef pyramid = build.graph.createImage(
        "indirect.flux_pyramid", VK_FORMAT_R32_SFLOAT, {padded / 2, padded}, usage, persistent);
    out.list = build.graph.createImage("indirect.vpl_list", VK_FORMAT_R32G32B32A32_SFLOAT,
                                       {uint32_t(count) + 1, 3}, usage);

    shader::VplDrawConstants c{};
    c.cached = moving ? 1 : 0;
    c.mapSize = int(mapSize);
    c.vplMapSize = int(vplMapSize);
    c.paddedSize = int(padded);
    c.levels = int(levels);
    using graph::Use;
    for (int stage = 0; stage < 2; ++stage) {
        // Stage 0 writes the VPL map, stage 1 reads it (imageLoad: the shader is one). Stage 1
        // declares it StorageReadWrite all the same: the shader's image2D bindings are not
        // readonly (stage 0 writes them), so synchronization validation counts stage 1's dispatch
        // as a write, and a StorageRead left the gather's layout transition without that write in
        // its source scope (SYNC-HAZARD-WRITE-AFTER-WRITE from the second cached frame on).
        const Use map = stage == 0 ? Use::StorageWrite : Use::StorageReadWrite;
        ComputePassDesc pass{stage == 0 ? "indirect.flux" : "indirect.vpls", "indirect_vpls.comp"};
        pass.images = {
            {"rsmVpls", in.rsm.vpls, Use::Sampled},
            {"vplPosition", out.position, map},
            {"vplNormal", out.normal, map},
            {"vplFlux", out.flux, map},
            {"fluxPyramid", pyramid, stage == 0 ? Use::StorageWrite : Use::StorageReadWrite},
            {"vplList", out.list, Use::StorageWrite}};
        pass.pushSize = sizeof(shader::VplDrawConstants);
        pass.spec = {{{"STAGE", stage}, {"FLUX_VPLS", count}, {"CLUSTER", int(clusterSide)}}};
        // Stage 0: an 8 x 8 group per 8 x 8 VPLs of the padded map; stage 1: one group.
        const uint32_t side = stage == 0 ? padded : 8;
        graph::EnabledFn enabled;
        if (stage == 0 && persistent)
            enabled = [](const FrameState& frame) { return frame.drawRsm; };
        addComputePass(
            build, std::move(pass),
            [side, c](const ComputeRecorder& r) { r.dispatch(side, side, c); }, std::move(enabled));
    }
    return out;
}

} // namespace ssgi
