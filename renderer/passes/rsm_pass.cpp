// rsm: the light's view of the scene; its depth is the shadow map, its texels the virtual
// point lights of the one-bounce indirect light.
#include "passes/pass_setup.h"

namespace ssgi {

Rsm addRsmPass(PassSetup& s) {
    // A static light sees the same scene every frame: with the cache on, its map is drawn once
    // and again only after the light moves.
    std::function<bool()> enabled;
    if (s.model.settings.cache) enabled = [&s] { return s.rsmStale; };
    // One texel a VPL, all of it in one read (rsm_vpl.glsl). Its flux is albedo x light colour x
    // a 32-bit float share: the flux itself, about 1e-6 of the intensity, lost 6% of the bunny's
    // bounce in 16-bit floats and all of it for the same scene in centimetres (issue 18).
    const SceneTargets t =
        addScenePass(s, "rsm", "rsm", s.rsmSize, {{".vpls", VK_FORMAT_R32G32B32A32_UINT}}, enabled);
    return {t.colors[0], t.depth};
}

} // namespace ssgi
