// reprojection: where each pixel's surface lay in last frame's image, and which history texels
// hold it, once a frame for every cached effect (reproject.comp; temporal.glsl reads it). Not on
// a settled frame, which computes no effect: the image is persistent and keeps what it held. Before
// the G-buffer has a history, nothing is found anywhere.
//   reads:  gbuffer.view_depth, gbuffer.normal, last frame's gbuffer.view_depth
//   writes: reprojection (R32UI: reprojection.glsl packReprojection)
// Without the cache the image is a texel that nothing writes: what the effects' passes bind in
// its place (an unsigned image, as their shaders declare), which they never read.
#include "passes/passes.h"

namespace ssgi {

void addReprojectionPass(FrameBuild& build, const GBuffer& gbuffer) {
    const bool cached = build.settings.cache;
    const graph::ImageRef image = build.graph.createImage(
        "reprojection", VK_FORMAT_R32_UINT, cached ? build.size : VkExtent2D{1, 1},
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, /*persistent=*/true);
    build.caches.reprojection = image;
    if (!cached) return;
    using graph::FrameGraph;
    using graph::Use;
    const uint32_t history = *build.caches.viewDepthHistory;
    ComputePassDesc pass{"reprojection", "reproject.comp"};
    pass.images = {{"gbufferViewDepth", gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", gbuffer.normal, Use::Sampled},
                   {"historyViewDepth", FrameGraph::previous(history), Use::Sampled},
                   {"reprojectionImage", image, Use::StorageWrite}};
    pass.pushSize = sizeof(shader::ReprojectionConstants);
    addComputePass(build, std::move(pass), [&build, history](const ComputeRecorder& r) {
        const shader::ReprojectionConstants constants =
            reprojectionConstants(build.settings, build.graph.hasHistory(history));
        const bool settled = r.frame().settled;
        r.dispatch(settled ? 0 : build.size.width, settled ? 0 : build.size.height, constants);
    });
}

} // namespace ssgi
