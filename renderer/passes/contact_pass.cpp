// contact: screen-space contact shadows (SSDO paper section 5) on top of the shadow term, where
// the shadow map's bias lets light leak under the objects that cast the shadows.
#include "passes/passes.h"

#include "shared.h"

namespace ssgi {

graph::ImageRef addContactPass(FrameBuild& build, const GBufferAndRsm& in, graph::ImageRef shadow) {
    const graph::ImageRef contact =
        build.graph.createImage("contact", VK_FORMAT_R16G16B16A16_SFLOAT, build.size,
                                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    using graph::Use;
    ComputePassDesc pass{"contact", "contact.comp"};
    pass.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"shadowImage", shadow, Use::Sampled},
                   secondLayerInput(in),
                   {"contactShadow", contact, Use::StorageWrite}};
    pass.pushSize = sizeof(shader::ContactConstants);
    pass.spec = {{{"STEPS", int(build.settings.contact_shadow_steps)},
                  {"PEELING", in.secondLayer.valid() ? 1 : 0}}};
    addComputePass(build, std::move(pass), [&build](const ComputeRecorder& r) {
        shader::ContactConstants constants{};
        constants.segmentTexels = float(build.settings.contact_shadow_texels);
        r.dispatch(build.size.width, build.size.height, constants);
    });
    return contact;
}

} // namespace ssgi
