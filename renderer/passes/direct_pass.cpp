// direct: radiance from the spot light at every G-buffer pixel, times the shadow term.
#include "passes/pass_setup.h"

namespace ssgi {

graph::ImageRef addDirectPass(PassSetup& s, const GBufferAndRsm& in, graph::ImageRef shadow) {
    graph::ImageRef direct =
        s.graph.createImage("direct", VK_FORMAT_R16G16B16A16_SFLOAT, s.size,
                            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    using graph::Use;
    ComputePassDesc pass{"direct", "direct.comp"};
    pass.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"gbufferAlbedo", in.gbuffer.albedo, Use::Sampled},
                   {"shadowImage", shadow, Use::Sampled},
                   {"directRadiance", direct, Use::StorageWrite}};
    addComputePass(s, std::move(pass),
                   [&s](const ComputeRecorder& r) { r.dispatch(s.size.width, s.size.height); });
    return direct;
}

} // namespace ssgi
