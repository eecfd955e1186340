// composite: the direct light and the lighting terms added up into HDR radiance, then
// tonemapped to an sRGB image (or a debug view of any intermediate in its place).
//   reads:  gbuffer.view_depth, .normal, .albedo, direct, the shadow term, rsm.vpls (its views),
//           peel.position (its view), and each lighting term the passes handed it
//           (FrameBuild::compositeTerms), in slots term0..term3 with their roles
//   writes: hdr, ldr
#include "passes/passes.h"
#include "passes/views.h"

#include <string>

namespace ssgi {

CompositeOutputs addCompositePass(FrameBuild& build, const GBufferAndRsm& in,
                                  const CompositeImages& images) {
    const VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    CompositeOutputs out;
    const VkExtent2D output = build.output().extent;
    // Three 21-bit floats in two words (shared.h HDR_*): a float's range, as the EXR keeps what
    // half floats cannot hold (image_io.cpp), in half the bytes of RGBA32F.
    out.hdr = build.graph.createImage("hdr", VK_FORMAT_R32G32_UINT, output, storage);
    out.ldr = build.graph.createImage("ldr", VK_FORMAT_R8G8B8A8_UNORM, output, storage);
    using graph::Use;
    ComputePassDesc pass{"composite", "composite.comp"};
    pass.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"gbufferAlbedo", in.gbuffer.albedo, Use::Sampled},
                   {"directRadiance", images.direct, Use::Sampled},
                   {"shadowImage", images.shadow, Use::Sampled},
                   {"rsmVpls", in.rsm.vpls, Use::Sampled},
                   // The shader reads the second layer only for its view, when there is one.
                   secondLayerInput(in)};
    pass.spec = {{{"HAS_CONTACT", build.settings.contact_shadows ? 1 : 0}}};
    // Each slot's role is structural: a slot without a term (TERM_NONE) is never read, and holds
    // the direct light so that every binding holds a valid image.
    const std::vector<CompositeTerm>& terms = build.compositeTerms;
    for (size_t slot = 0; slot < COMPOSITE_TERMS; ++slot) {
        const bool used = slot < terms.size();
        const std::string name = "term" + std::to_string(slot);
        pass.images.push_back({name, used ? terms[slot].image : images.direct, Use::Sampled});
        pass.spec.constants.push_back(
            {"TERM" + std::to_string(slot) + "_ROLE", used ? terms[slot].role : TERM_NONE});
    }
    pass.images.push_back({"hdrImage", out.hdr, Use::StorageWrite});
    pass.images.push_back({"ldrImage", out.ldr, Use::StorageWrite});
    pass.pushSize = sizeof(shader::CompositeConstants);
    // Each view's term slot, -1 for the composite's own views and for terms this frame lacks.
    std::vector<int> termSlots(std::size(kViews), -1);
    for (size_t v = 0; v < std::size(kViews); ++v) {
        const char* term = kViews[v].showsTerm ? kViews[v].showsTerm : kViews[v].name;
        for (size_t slot = 0; slot < terms.size(); ++slot)
            if (terms[slot].view == term) termSlots[v] = int(slot);
    }
    addComputePass(build, std::move(pass), [&build, output, termSlots](const ComputeRecorder& r) {
        shader::CompositeConstants constants{};
        constants.view = kViews[r.frame().view].view;
        constants.guardBand = int(build.guardBand);
        constants.termSlot = termSlots[size_t(r.frame().view)];
        constants.termRole = kViews[r.frame().view].role;
        r.dispatch(output.width, output.height, constants);
    });
    return out;
}

} // namespace ssgi
