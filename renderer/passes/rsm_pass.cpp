// rsm: the light's view of the scene; its depth is the shadow map, its texels the virtual
// point lights of the one-bounce indirect light.
#include "passes/passes.h"

namespace ssgi {

Rsm addRsmPass(FrameBuild& build) {
    // A static light sees the same scene every frame: with the cache on, its map is drawn once
    // and again only after the light moves (FrameState::drawRsm).
    graph::EnabledFn enabled;
    if (build.settings.cache) enabled = [](const FrameState& frame) { return frame.drawRsm; };
    // One texel a VPL, all of it in one read (rsm_vpl.glsl). Its flux is albedo x light colour x
    // a 32-bit float share: the flux itself is about 1e-6 of the intensity, below what a 16-bit
    // float keeps for a scene in small units.
    const SceneTargets t = addScenePass(build, "rsm", "rsm", build.rsmSize,
                                        {{".vpls", VK_FORMAT_R32G32B32A32_UINT}}, enabled);
    return {t.colors[0], t.depth};
}

} // namespace ssgi
