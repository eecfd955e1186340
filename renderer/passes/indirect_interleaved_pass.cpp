// indirect + indirect.filter_x + indirect.filter_y: one-bounce indirect light from the RSM's
// virtual point lights with interleaved sampling (indirect_method 1): each pixel gathers 1/k^2 of
// the VPLs at full resolution (indirect_interleaved.comp), then a geometry-aware filter, one axis a
// pass (indirect_reconstruct.comp), gives every pixel the whole set's estimate many times over
// (Keller and Heidrich 2001; Segovia et al. 2006). No upsampling, so no staircase, and no pixel
// gathers every VPL.
//   reads:  gbuffer.position, gbuffer.normal, rsm.position, rsm.normal, rsm.flux, last frame's
//           gbuffer.position and the cache's indirect.count (to skip converged pixels)
//   writes: indirect + indirect.directional (each pixel's subset: irradiance / pi, and the L1
//           sums of its VPLs' light), indirect.filtered_x + .filtered_x_directional (after the
//           x axis), indirect again (after the y axis: the result; the y pass binds
//           indirect.directional, unused by then, as its directional target and writes none)
#include "passes/pass_setup.h"

#include "shared.h"

#include <algorithm>
#include <cmath>

namespace ssgi {

graph::ImageRef addInterleavedIndirectPasses(PassSetup& s, const GBufferAndRsm& in,
                                             EffectCache* cache) {
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    auto image = [&](const char* name) {
        return s.graph.createImage(name, VK_FORMAT_R16G16B16A16_SFLOAT, s.size, usage);
    };
    // Four full-resolution images: the subsets' estimates go into `indirect`, which the y axis
    // overwrites with the result once the x axis has read them (`result` below).
    const graph::ImageRef subsets = image("indirect");
    const graph::ImageRef subsetsDirectional = image("indirect.directional");
    const graph::ImageRef across = image("indirect.filtered_x");
    const graph::ImageRef acrossDirectional = image("indirect.filtered_x_directional");
    // k^2 subsets of at least one VPL each: k at most the square root of the VPL count.
    const int vpls = int(s.model.settings.indirect_vpls);
    const int k =
        std::min(int(s.model.settings.indirect_interleave), int(std::sqrt(double(vpls)) + 1e-9));
    const int radius = int(s.model.settings.indirect_filter_radius);
    // On settled frames the refresh tile's pixels need their neighbours: the gather and the x
    // axis run over the tile widened by the filter's reach (temporal.glsl cachePixelAround).
    const uint32_t margin = uint32_t(std::max(radius, k / 2));
    auto dispatchArea = [&s, cache](uint32_t widen) {
        VkExtent2D area = cacheDispatch(s, cache, s.size);
        if (cache && s.settled && area.width > 0)
            area = {area.width + 2 * widen, area.height + 2 * widen};
        return area;
    };
    const vk::Pipeline gather = s.computePipeline(
        "indirect_interleaved.comp", 7, 2, sizeof(shader::IndirectConstants),
        vk::Specialization{{vpls, int(s.model.settings.indirect_visibility),
                            int(s.model.settings.indirect_visibility_steps), k, radius}});
    const vk::Pipeline filter =
        s.computePipeline("indirect_reconstruct.comp", 6, 2, sizeof(shader::IndirectConstants),
                          vk::Specialization{{k, radius}});

    const CacheInputs history = cacheInputs(s, cache, in.gbuffer.position);
    auto constants = [&s, cache](glm::ivec2 axis) {
        shader::IndirectConstants c{};
        c.rotation = s.patternRotation;
        c.scale = s.patternScale;
        c.radius = float(s.model.settings.indirect_radius);
        c.radialOffset = radialOffset(s, cache);
        c.width = int(s.size.width);
        c.height = int(s.size.height);
        c.axisX = axis.x;
        c.axisY = axis.y;
        c.cache = cacheConstants(s, cache);
        return c;
    };

    addKeepPass(s, cache, {subsets, subsetsDirectional, across, acrossDirectional});
    using graph::Use;
    s.graph.addPass("indirect", graph::PassKind::Compute,
                    {{in.gbuffer.position, Use::Sampled},
                     {in.gbuffer.normal, Use::Sampled},
                     {in.rsm.position, Use::Sampled},
                     {in.rsm.normal, Use::Sampled},
                     {in.rsm.third, Use::Sampled},
                     {history.position, Use::Sampled},
                     {history.count, Use::Sampled},
                     {subsets, Use::StorageWrite},
                     {subsetsDirectional, Use::StorageWrite}},
                    [&s, in, history, subsets, subsetsDirectional, gather, dispatchArea, margin,
                     constants](const graph::PassContext& pc) {
                        vk::Descriptors()
                            .uniformBuffer(0, s.frameUniforms.buffer, s.frameUniforms.size)
                            .sampledImage(1, pc.image(in.gbuffer.position).view, s.nearestSampler)
                            .sampledImage(2, pc.image(in.gbuffer.normal).view, s.nearestSampler)
                            .sampledImage(3, pc.image(in.rsm.position).view, s.nearestSampler)
                            .sampledImage(4, pc.image(in.rsm.normal).view, s.nearestSampler)
                            .sampledImage(5, pc.image(in.rsm.third).view, s.nearestSampler)
                            .sampledImage(6, pc.image(history.position).view, s.nearestSampler)
                            .sampledImage(7, pc.image(history.count).view, s.nearestSampler)
                            .storageImage(8, pc.image(subsets).view)
                            .storageImage(9, pc.image(subsetsDirectional).view)
                            .push(s.ctx, pc.cmd, gather);
                        const VkExtent2D area = dispatchArea(margin);
                        vk::dispatch(pc.cmd, gather, area.width, area.height, constants({0, 0}));
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
        s.graph.addPass(
            a.pass, graph::PassKind::Compute,
            {{in.gbuffer.position, Use::Sampled},
             {in.gbuffer.normal, Use::Sampled},
             {history.position, Use::Sampled},
             {history.count, Use::Sampled},
             {a.source, Use::Sampled},
             {a.sourceDirectional, Use::Sampled},
             {a.target, Use::StorageWrite},
             {a.targetDirectional, Use::StorageWrite}},
            [&s, in, history, a, filter, constants, dispatchArea,
             margin](const graph::PassContext& pc) {
                vk::Descriptors()
                    .uniformBuffer(0, s.frameUniforms.buffer, s.frameUniforms.size)
                    .sampledImage(1, pc.image(in.gbuffer.position).view, s.nearestSampler)
                    .sampledImage(2, pc.image(in.gbuffer.normal).view, s.nearestSampler)
                    .sampledImage(3, pc.image(history.position).view, s.nearestSampler)
                    .sampledImage(4, pc.image(history.count).view, s.nearestSampler)
                    .sampledImage(5, pc.image(a.source).view, s.nearestSampler)
                    .sampledImage(6, pc.image(a.sourceDirectional).view, s.nearestSampler)
                    .storageImage(7, pc.image(a.target).view)
                    .storageImage(8, pc.image(a.targetDirectional).view)
                    .push(s.ctx, pc.cmd, filter);
                const VkExtent2D area = dispatchArea(a.axis.x == 1 ? margin : 0);
                vk::dispatch(pc.cmd, filter, area.width, area.height, constants(a.axis));
            });
    }
    return subsets; // the y axis's result
}

} // namespace ssgi
