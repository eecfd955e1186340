// contact: screen-space contact shadows (SSDO paper section 5) on top of the shadow term, where
// the shadow map's bias lets light leak under the objects that cast the shadows.
#include "passes/pass_setup.h"

#include "shared.h"

namespace ssgi {

graph::ImageRef addContactPass(PassSetup& s, const GBufferAndRsm& in, graph::ImageRef shadow,
                               graph::ImageRef secondLayer) {
    const graph::ImageRef contact =
        s.graph.createImage("contact", VK_FORMAT_R16G16B16A16_SFLOAT, s.size,
                            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    const vk::Pipeline pipeline = s.computePipeline(
        "contact.comp", 4, 1, sizeof(shader::ContactConstants),
        {{int(s.model.settings.contact_shadow_steps), secondLayer.valid() ? 1 : 0}});
    // Without the second layer the shader never reads binding 4; the shadow term stands in.
    const graph::ImageRef back = secondLayer.valid() ? secondLayer : shadow;
    using graph::Use;
    s.graph.addPass("contact", graph::PassKind::Compute,
                    {{in.gbuffer.position, Use::Sampled},
                     {in.gbuffer.normal, Use::Sampled},
                     {shadow, Use::Sampled},
                     {back, Use::Sampled},
                     {contact, Use::StorageWrite}},
                    [&s, in, shadow, back, contact, pipeline](const graph::PassContext& pc) {
                        vk::Descriptors()
                            .uniformBuffer(0, s.frameUniforms.buffer, s.frameUniforms.size)
                            .sampledImage(1, pc.image(in.gbuffer.position).view, s.nearestSampler)
                            .sampledImage(2, pc.image(in.gbuffer.normal).view, s.nearestSampler)
                            .sampledImage(3, pc.image(shadow).view, s.nearestSampler)
                            .sampledImage(4, pc.image(back).view, s.nearestSampler)
                            .storageImage(5, pc.image(contact).view)
                            .push(s.ctx, pc.cmd, pipeline);
                        shader::ContactConstants constants{};
                        constants.segmentTexels = float(s.model.settings.contact_shadow_texels);
                        vk::dispatch(pc.cmd, pipeline, s.size.width, s.size.height, constants);
                    });
    return contact;
}

} // namespace ssgi
