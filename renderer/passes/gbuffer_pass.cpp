// gbuffer: the camera's view of the scene, what every screen-space pass reads. With caching on
// its view depths (and so its world positions) are a history pair: last frame's are what the
// caches reproject against.
#include "passes/pass_setup.h"

namespace ssgi {

SceneTargets addGBufferPass(PassSetup& s) {
    return addScenePass(s, "gbuffer", "gbuffer", s.size, true, VK_FORMAT_R8G8B8A8_UNORM, {},
                        s.model.settings.cache ? &s.viewDepthHistory : nullptr);
}

} // namespace ssgi
