// rsm: the light's view of the scene; its depth is the shadow map, its texels the virtual
// point lights of the one-bounce indirect light.
#include "passes/pass_setup.h"

namespace ssgi {

SceneTargets addRsmPass(PassSetup& s) {
    // A static light sees the same scene every frame: with the cache on, its map is drawn once
    // and again only after the light moves.
    std::function<bool()> enabled;
    if (s.model.setting("cache") != 0.0) enabled = [&s] { return s.rsmStale; };
    return addScenePass(s, "rsm", "rsm", s.rsmSize, VK_FORMAT_R16G16B16A16_SFLOAT, enabled);
}

} // namespace ssgi
