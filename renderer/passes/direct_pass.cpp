// direct: radiance from the spot light at every G-buffer pixel, times the shadow term.
#include "passes/passes.h"

namespace ssgi {

graph::ImageRef addDirectPass(FrameBuild& build, const GBufferAndRsm& in, graph::ImageRef shadow) {
    graph::ImageRef direct =
        build.graph.createImage("direct", VK_FORMAT_R16G16B16A16_SFLOAT, build.size,
                                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    using graph::Use;
    ComputePassDesc pass{"direct", "direct.comp"};
    pass.images = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"gbufferAlbedo", in.gbuffer.albedo, Use::Sampled},
                   {"shadowImage", shadow, Use::Sampled},
                   {"directRadiance", direct, Use::StorageWrite}};
    addComputePass(build, std::move(pass), [&build](const ComputeRecorder& r) {
        r.dispatch(build.size.width, build.size.height);
    });
    return direct;
}

} // namespace ssgi
