// gbuffer: the camera's view of the scene, what every screen-space pass reads. With caching on
// its view depths (and so its world positions) are a history pair: last frame's are what the
// caches reproject against; and its images are kept from frame to frame, drawn again only when
// the camera or an object moved in the last two frames (FrameState::drawGBuffer).
#include "passes/passes.h"

namespace ssgi {

GBuffer addGBufferPass(FrameBuild& build) {
    graph::EnabledFn enabled;
    if (build.settings.cache) enabled = [](const FrameState& frame) { return frame.drawGBuffer; };
    const SceneTargets t =
        addScenePass(build, "gbuffer", "gbuffer", build.size,
                     {{".view_depth", VK_FORMAT_R32_SFLOAT},
                      {".normal", VK_FORMAT_R16G16B16A16_SFLOAT},
                      {".albedo", VK_FORMAT_R8G8B8A8_UNORM}},
                     enabled, build.settings.cache ? &build.caches.viewDepthHistory : nullptr,
                     OpaqueDraws::Shaded, DepthTarget::DrawOnly);
    return {t.colors[0], t.colors[1], t.colors[2], t.depth};
}

} // namespace ssgi
