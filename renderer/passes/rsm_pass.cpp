// rsm: the light's view of the scene; its depth is the shadow map, its texels the virtual
// point lights of the one-bounce indirect light.
#include "passes/pass_setup.h"

namespace ssgi {

SceneTargets addRsmPass(PassSetup& s) {
    // A static light sees the same scene every frame: with the cache on, its map is drawn once
    // and again only after the light moves.
    std::function<bool()> enabled;
    if (s.model.settings.cache) enabled = [&s] { return s.rsmStale; };
    // The flux in 32-bit floats: a texel's flux is its intensity times a solid angle of about
    // 1e-6 sr, which in 16-bit floats lost 6% of the bunny's bounce and all of it for the same
    // scene in centimetres (issue 18).
    return addScenePass(s, "rsm", "rsm", s.rsmSize, false, VK_FORMAT_R32G32B32A32_SFLOAT, enabled);
}

} // namespace ssgi
