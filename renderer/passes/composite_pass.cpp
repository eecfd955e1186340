// composite: the frame's terms added up into HDR radiance, then tonemapped to an sRGB image
// (or a debug view of any intermediate in its place).
#include "passes/passes.h"

namespace ssgi {

CompositeOutputs addCompositePass(FrameBuild& build, const GBufferAndRsm& in,
                                  const LightingTerms& terms) {
    const VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    CompositeOutputs out;
    const VkExtent2D output = build.output().extent;
    out.hdr = build.graph.createImage("hdr", VK_FORMAT_R32G32B32A32_SFLOAT, output, storage);
    out.ldr = build.graph.createImage("ldr", VK_FORMAT_R8G8B8A8_UNORM, output, storage);
    // Which terms exist is structural: the shader never reads the image bound in place of an
    // effect that is off (the direct term, so that every binding holds a valid image).
    auto orDirect = [&](graph::ImageRef ref) { return ref.valid() ? ref : terms.direct; };
    using graph::Use;
    ComputePassDesc pass{"composite", "composite.comp"};
    pass.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"gbufferAlbedo", in.gbuffer.albedo, Use::Sampled},
                   {"directRadiance", terms.direct, Use::Sampled},
                   {"shadowImage", terms.shadow, Use::Sampled},
                   {"aoImage", orDirect(terms.ao), Use::Sampled},
                   {"indirectImage", orDirect(terms.indirect), Use::Sampled},
                   {"ssdoImage", orDirect(terms.ssdo), Use::Sampled},
                   {"rsmVpls", in.rsm.vpls, Use::Sampled},
                   {"secondLayer", orDirect(terms.secondLayer), Use::Sampled},
                   {"skyVisibilityImage", orDirect(terms.skyVisibility), Use::Sampled},
                   {"hdrImage", out.hdr, Use::StorageWrite},
                   {"ldrImage", out.ldr, Use::StorageWrite}};
    pass.pushSize = sizeof(shader::CompositeConstants);
    pass.spec = {{{"HAS_AO", terms.ao.valid() ? 1 : 0},
                  {"HAS_INDIRECT", terms.indirect.valid() ? 1 : 0},
                  {"HAS_SSDO", terms.ssdo.valid() ? 1 : 0},
                  {"HAS_SKY_VISIBILITY", terms.skyVisibility.valid() ? 1 : 0},
                  {"HAS_CONTACT", build.settings.contact_shadows ? 1 : 0}}};
    addComputePass(build, std::move(pass), [&build, output](const ComputeRecorder& r) {
        shader::CompositeConstants constants{};
        constants.view = r.frame().view;
        constants.guardBand = int(build.guardBand);
        r.dispatch(output.width, output.height, constants);
    });
    return out;
}

} // namespace ssgi
