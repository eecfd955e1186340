// composite: the frame's terms added up into HDR radiance, then tonemapped to an sRGB image
// (or a debug view of any intermediate in its place).
#include "passes/pass_setup.h"

#include "shared.h"

namespace ssgi {

CompositeOutputs addCompositePass(PassSetup& s, const GBufferAndRsm& in,
                                  const LightingTerms& terms) {
    const VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    CompositeOutputs out;
    const VkExtent2D output = s.output().extent;
    out.hdr = s.graph.createImage("hdr", VK_FORMAT_R32G32B32A32_SFLOAT, output, storage);
    out.ldr = s.graph.createImage("ldr", VK_FORMAT_R8G8B8A8_UNORM, output, storage);
    // Which terms exist is structural: the shader never reads the image bound in place of an
    // effect that is off (the direct term, so that every binding holds a valid image).
    const vk::Pipeline pipeline =
        s.computePipeline("composite.comp", 12, 2, sizeof(shader::CompositeConstants),
                          {{terms.ao.valid() ? 1 : 0, terms.indirect.valid() ? 1 : 0,
                            terms.ssdo.valid() ? 1 : 0, terms.skyVisibility.valid() ? 1 : 0}});
    auto orDirect = [&](graph::ImageRef ref) { return ref.valid() ? ref : terms.direct; };
    const graph::ImageRef inputs[12] = {in.gbuffer.position,
                                        in.gbuffer.normal,
                                        in.gbuffer.third,
                                        terms.direct,
                                        terms.shadow,
                                        orDirect(terms.ao),
                                        orDirect(terms.indirect),
                                        orDirect(terms.ssdo),
                                        in.rsm.third,
                                        in.rsm.normal,
                                        orDirect(terms.secondLayer),
                                        orDirect(terms.skyVisibility)};

    std::vector<graph::ImageUse> uses;
    for (const graph::ImageRef& ref : inputs)
        uses.push_back({ref, graph::Use::Sampled});
    uses.push_back({out.hdr, graph::Use::StorageWrite});
    uses.push_back({out.ldr, graph::Use::StorageWrite});
    std::vector<graph::ImageRef> sampled(std::begin(inputs), std::end(inputs));
    s.graph.addPass("composite", graph::PassKind::Compute, uses,
                    [&s, sampled, out, output, pipeline](const graph::PassContext& pc) {
                        vk::Descriptors d;
                        d.uniformBuffer(0, s.frameUniforms.buffer, s.frameUniforms.size);
                        for (uint32_t i = 0; i < sampled.size(); ++i)
                            d.sampledImage(1 + i, pc.image(sampled[i]).view,
                                           i == 8 || i == 9 ? s.linearSampler : s.nearestSampler);
                        d.storageImage(13, pc.image(out.hdr).view)
                            .storageImage(14, pc.image(out.ldr).view)
                            .push(s.ctx, pc.cmd, pipeline);
                        shader::CompositeConstants constants{};
                        constants.view = s.view;
                        constants.guardBand = int(s.guardBand);
                        vk::dispatch(pc.cmd, pipeline, output.width, output.height, constants);
                    });
    return out;
}

} // namespace ssgi
