// shadow_map_back: the depth from the light of the nearest surface that faces away from it,
// for the shadow test's light-space horizons (shadow_variant 1, shadow.comp): where the map's
// depth says a ray from the light enters a solid, this says where it leaves it. Drawn on the
// shadow map's frames (shadow_map_pass.cpp), with shadow_map_back.vert/.frag.
//   reads:  the scene, the frame's light
//   writes: shadow_map_back.depth (D32, the far plane where no back face lies)
#include "passes/passes.h"

#include <algorithm>

namespace ssgi {

graph::ImageRef addShadowMapBackPass(FrameBuild& build) {
    // Half the map's side: where a solid ends needs less detail than where it begins, and the
    // pass discards (the facing test), so it costs more per texel than the map: on lavapipe,
    // Sponza at 256x256 took 103 ms at 2048 and 45 at 1024, the map 77; direct light against
    // the path tracer 0.00396 and 0.00405, the Cornell box's 0.00076 and 0.00092.
    const uint32_t side = std::max(uint32_t(build.settings.shadow_map_size) / 2, 16u);
    return addScenePass(build, "shadow_map_back", "shadow_map_back", VkExtent2D{side, side}, {},
                        onLightFrames(build))
        .depth;
}

} // namespace ssgi
