// indirect + indirect.filter_x + indirect.filter_y: one-bounce indirect light from the RSM's
// virtual point lights with interleaved sampling (indirect_method 1): each pixel gathers 1/k^2 of
// the VPLs at full resolution (indirect_interleaved.comp), then a geometry-aware filter, one axis a
// pass (indirect_reconstruct.comp), gives every pixel the whole set's estimate many times over
// (Keller and Heidrich 2001; Segovia et al. 2006). No upsampling, so no staircase, and no pixel
// gathers every VPL.
//   reads:  gbuffer.view_depth, gbuffer.normal, rsm.vpls, last frame's gbuffer.view_depth and
//           the cache's indirect.count (to skip converged pixels), light_depth_min (the
//           visibility test's light check); the filter also last frame's indirect.history (what
//           a skipped neighbour holds)
//   writes: indirect + indirect.directional (each pixel's subset: irradiance / pi, and the L1
//           sums of its VPLs' light), indirect.filtered_x (with the cache, this frame's side of
//           indirect.history, which the temporal pass overwrites) + .filtered_x_directional
//           (after the x axis), indirect again (after the y axis: the result; the y pass binds
//           indirect.directional, unused by then, as its directional target and writes none)
#include "passes/passes.h"

#include <algorithm>
#include <cmath>

namespace ssgi {

graph::ImageRef addInterleavedIndirectPasses(FrameBuild& build, const GBufferAndRsm& in,
                                             const EffectCache* cache, const FluxVpls* fluxVpls) {
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    auto image = [&](const char* name) {
        return build.graph.createImage(name, VK_FORMAT_R16G16B16A16_SFLOAT, build.size, usage);
    };
    // Four full-resolution images: the subsets' estimates go into `indirect`, which the y axis
    // overwrites with the result once the x axis has read them (`result` below). With the cache,
    // the x axis's estimates go into the side of the history pair that the frame's temporal pass
    // writes: nothing reads that side before then (the filter reads last frame's, the other), so
    // it serves as working memory and the four are never alive together in the shared block.
    const graph::ImageRef subsets = image("indirect");
    const graph::ImageRef subsetsDirectional = image("indirect.directional");
    const graph::ImageRef across =
        cache ? graph::FrameGraph::current(cache->valueHistory) : image("indirect.filtered_x");
    const graph::ImageRef acrossDirectional = image("indirect.filtered_x_directional");
    // k^2 subsets of at least one VPL each: k at most the square root of the VPL count.
    const int vpls = int(build.settings.indirect_vpls);
    const int k =
        std::min(int(build.settings.indirect_interleave), int(std::sqrt(double(vpls)) + 1e-9));
    const int radius = int(build.settings.indirect_filter_radius);
    const Settings& settings = build.settings;
    vk::Specialization gatherSpec{{{"VPLS", vpls},
                                   {"VISIBILITY", int(settings.indirect_visibility)},
                                   {"VISIBILITY_STEPS", int(settings.indirect_visibility_steps)},
                                   {"INTERLEAVE", k},
                                   {"RADIUS", radius},
                                   {"PEELING", in.secondLayer.valid() ? 1 : 0},
                                   {"LIGHT_CHECK", in.lightDepthMin.valid() ? 1 : 0}}};
    if (fluxVpls) { // method 2: its flux-drawn VPLs, the tests drawn, the pool, the map's side
        const int cluster = int(settings.indirect_vpl_cluster);
        gatherSpec.constants.insert(
            gatherSpec.constants.end(),
            {{"FLUX_VPLS", int(settings.indirect_flux_vpls)},
             {"TESTS", int(settings.indirect_visibility_tests)},
             {"POOL", int(std::max(settings.indirect_flux_pool, settings.indirect_flux_vpls))},
             {"MAP_SIZE", (int(build.rsmSize.width) + cluster - 1) / cluster}});
    }
    const vk::Specialization filterSpec{{{"INTERLEAVE", k}, {"RADIUS", radius}}};

    auto constants = [&build, cache](const FrameState& frame, glm::ivec2 axis) {
        shader::IndirectConstants c = indirectConstants(build, cache, frame, build.size);
        c.axisX = axis.x;
        c.axisY = axis.y;
        return c;
    };
    const std::vector<ShaderImage> cacheInputs = cacheBindings(build, cache, in.gbuffer.viewDepth);
    // The filter reads a skipped neighbour's history (any image the pass reads, without a cache).
    const graph::ImageRef history =
        cache ? graph::FrameGraph::previous(cache->valueHistory) : in.gbuffer.viewDepth;

    // `indirect` (the subsets, then the result) reads "skipped" on settled frames.
    addKeepPass(build, cache, {subsets});
    using graph::Use;
    // Method 1 gathers the RSM's texels; method 2 the VPL map's, and the flux's list.
    ComputePassDesc gather{"indirect",
                           fluxVpls ? "indirect_importance.comp" : "indirect_interleaved.comp"};
    gather.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                     {"gbufferNormal", in.gbuffer.normal, Use::Sampled}};
    if (fluxVpls)
        gather.images.insert(gather.images.end(),
                             {{"vplPosition", fluxVpls->position, Use::Sampled},
                              {"vplNormal", fluxVpls->normal, Use::Sampled},
                              {"vplFlux", fluxVpls->flux, Use::Sampled},
                              {"vplList", fluxVpls->list, Use::Sampled}});
    else
        gather.images.push_back({"rsmVpls", in.rsm.vpls, Use::Sampled});
    gather.images.insert(gather.images.end(), cacheInputs.begin(), cacheInputs.end());
    gather.images.insert(gather.images.end(),
                         {{"interleavedIndirect", subsets, Use::StorageWrite},
                          {"interleavedDirectional", subsetsDirectional, Use::StorageWrite},
                          secondLayerInput(in),
                          lightDepthMinInput(in)});
    gather.pushSize = sizeof(shader::IndirectConstants);
    gather.spec = gatherSpec;
    addComputePass(build, std::move(gather), [&build, cache, constants](const ComputeRecorder& r) {
        const VkExtent2D area = cacheDispatch(cache, r.frame(), build.size);
        r.dispatch(area.width, area.height, constants(r.frame(), {0, 0}));
    });
    // The filter, one axis a pass: x from the subsets, y from x's result.
    struct Axis {
        const char* pass;
        glm::ivec2 axis;
        graph::ImageRef source, sourceDirectional, target, targetDirectional;
    };
    const Axis axes[] = {
        {"indirect.filter_x", {1, 0}, subsets, subsetsDirectional, across, acrossDirectional},
        {"indirect.filter_y", {0, 1}, across, acrossDirectional, subsets, subsetsDirectional}};
    for (const Axis& a : axes) {
        ComputePassDesc filter{a.pass, "indirect_reconstruct.comp"};
        filter.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                         {"gbufferNormal", in.gbuffer.normal, Use::Sampled}};
        filter.images.insert(filter.images.end(), cacheInputs.begin(), cacheInputs.end());
        filter.images.insert(filter.images.end(),
                             {{"estimates", a.source, Use::Sampled},
                              {"directionals", a.sourceDirectional, Use::Sampled},
                              {"filtered", a.target, Use::StorageWrite},
                              {"filteredDirectional", a.targetDirectional, Use::StorageWrite},
                              {"historyValue", history, Use::Sampled}});
        filter.pushSize = sizeof(shader::IndirectConstants);
        filter.spec = filterSpec;
        addComputePass(build, std::move(filter),
                       [axis = a.axis, &build, cache, constants](const ComputeRecorder& r) {
                           const VkExtent2D area = cacheDispatch(cache, r.frame(), build.size);
                           r.dispatch(area.width, area.height, constants(r.frame(), axis));
                       });
    }
    return subsets; // the y axis's result
}

} // namespace ssgi
