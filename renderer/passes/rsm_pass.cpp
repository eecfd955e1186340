// rsm: the light's view of the scene; its depth is the shadow map, its texels the virtual
// point lights of the one-bounce indirect light.
#include "passes/passes.h"

namespace ssgi {

// A static light sees the same scene every frame: with the cache on, its maps are drawn once
// and again only after the light moves.
graph::EnabledFn onLightFrames(const FrameBuild& build) {
    if (!build.settings.cache) return {};
    return [](const FrameState& frame) { return frame.drawRsm; };
}

Rsm addRsmPass(FrameBuild& build) {
    // One texel a VPL, all of it in one read (rsm_vpl.glsl). Its flux is albedo x light colour x
    // a 32-bit float share: the flux itself is about 1e-6 of the intensity, below what a 16-bit
    // float keeps for a scene in small units.
    const SceneTargets t =
        addScenePass(build, "rsm", "rsm", build.rsmSize, {{".vpls", VK_FORMAT_R32G32B32A32_UINT}},
                     onLightFrames(build));
    return {t.colors[0], t.depth};
}

} // namespace ssgi
