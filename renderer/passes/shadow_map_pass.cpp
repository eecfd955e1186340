// shadow_map: the light's depth alone, at shadow_map_size, for the shadow test (shadow.comp).
// The RSM (rsm_pass.cpp) holds a VPL a texel and needs no more of them than the bounce's
// patterns sample; a shadow edge needs finer texels than that: at 2048 against the RSM's 1024,
// Sponza's one frame 0.0120 -> 0.0093 against the converged reference (docs/effects.md). Where
// the two sizes are equal the RSM's own depth is the map, and no pass is drawn.
#include "passes/passes.h"

namespace ssgi {

graph::ImageRef addShadowMapPass(FrameBuild& build, const Rsm& rsm) {
    const uint32_t side = uint32_t(build.settings.shadow_map_size);
    if (side == build.rsmSize.width) return rsm.depth;
    // Drawn on the RSM's frames: after the light moved, or every frame without the cache.
    // The opaque materials' draws with no fragment shader; the alpha-masked ones' with
    // shadow_map.frag, which discards where the mask does.
    return addScenePass(build, "shadow_map", "shadow_map", VkExtent2D{side, side}, {},
                        onLightFrames(build), nullptr, OpaqueDraws::DepthOnly)
        .depth;
}

} // namespace ssgi
