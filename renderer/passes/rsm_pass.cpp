// rsm: the light's view of the scene; its depth is the shadow map, its texels the virtual
// point lights of the one-bounce indirect light.
#include "passes/pass_setup.h"

namespace ssgi {

SceneTargets addRsmPass(PassSetup& s) {
    return addScenePass(s, "rsm", "rsm", s.rsmSize, VK_FORMAT_R16G16B16A16_SFLOAT);
}

} // namespace ssgi
