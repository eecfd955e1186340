// indirect + upsample: one-bounce indirect light from the RSM's virtual point lights, gathered
// at half resolution and brought to full resolution from geometry-compatible neighbours; the
// pixels without one are gathered at full resolution (thesis 3.3 and ch. 4).
#include "passes/passes.h"

namespace ssgi {

graph::ImageRef addIndirectPasses(FrameBuild& build, const GBufferAndRsm& in,
                                  const EffectCache* cache) {
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const VkExtent2D halfSize{(build.size.width + 1) / 2, (build.size.height + 1) / 2};
    graph::ImageRef half =
        build.graph.createImage("indirect.half", VK_FORMAT_R16G16B16A16_SFLOAT, halfSize, usage);
    graph::ImageRef full =
        build.graph.createImage("indirect", VK_FORMAT_R16G16B16A16_SFLOAT, build.size, usage);
    vk::Specialization gatherSpec{
        {{"VPLS", int(build.settings.indirect_vpls)},
         {"VISIBILITY", int(build.settings.indirect_visibility)},
         {"VISIBILITY_STEPS", int(build.settings.indirect_visibility_steps)}}};
    vk::Specialization upsampleSpec = gatherSpec;
    upsampleSpec.constants.push_back({"HALF_RES", int(build.settings.indirect_half_res)});
    upsampleSpec.constants.push_back({"PEELING", in.secondLayer.valid() ? 1 : 0});
    gatherSpec.constants.push_back({"PEELING", in.secondLayer.valid() ? 1 : 0});
    const vk::SpecConstant lightCheck{"LIGHT_CHECK", in.lightDepthMin.valid() ? 1 : 0};
    gatherSpec.constants.push_back(lightCheck);
    upsampleSpec.constants.push_back(lightCheck);
    const ShaderImage secondLayer = secondLayerInput(in);
    const ShaderImage lightDepthMin = lightDepthMinInput(in);
    const bool halfRes = build.settings.indirect_half_res;
    auto constants = [&build, halfSize, cache](const FrameState& frame) {
        return indirectConstants(build, cache, frame, halfSize);
    };

    addKeepPass(build, cache, {half, full});
    using graph::Use;
    std::vector<ShaderImage> reads = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                                      {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                                      {"rsmVpls", in.rsm.vpls, Use::Sampled}};
    for (ShaderImage& history : cacheBindings(build, cache, in.gbuffer.viewDepth))
        reads.push_back(std::move(history));
    ComputePassDesc gather{"indirect", "indirect.comp", reads};
    gather.images.push_back({"halfIndirect", half, Use::StorageWrite});
    gather.images.push_back(secondLayer);
    gather.images.push_back(lightDepthMin);
    gather.pushSize = sizeof(shader::IndirectConstants);
    gather.spec = gatherSpec;
    addComputePass(
        build, std::move(gather),
        [&build, cache, constants](const ComputeRecorder& r) {
            const VkExtent2D area = cacheDispatch(cache, r.frame(), build.size);
            r.dispatch(area.width, area.height, constants(r.frame()));
        },
        // At full resolution the upsampling gathers every pixel itself.
        [halfRes](const FrameState&) { return halfRes; });

    ComputePassDesc upsample{"upsample", "upsample.comp", reads};
    upsample.images.push_back({"halfIndirect", half, Use::Sampled});
    upsample.images.push_back({"indirectImage", full, Use::StorageWrite});
    upsample.images.push_back(secondLayer);
    upsample.images.push_back(lightDepthMin);
    upsample.pushSize = sizeof(shader::IndirectConstants);
    upsample.spec = upsampleSpec;
    addComputePass(build, std::move(upsample),
                   [&build, cache, constants](const ComputeRecorder& r) {
                       const VkExtent2D area = cacheDispatch(cache, r.frame(), build.size);
                       r.dispatch(area.width, area.height, constants(r.frame()));
                   });
    return full;
}

} // namespace ssgi
