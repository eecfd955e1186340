// The one-bounce indirect light as a cached effect: its cache declared once, then the passes of
// the method the settings choose (indirect_method: 0 the thesis's half-resolution gather and its
// upsampling, 1 interleaved VPL subsets and their filter, 2 the same with VPLs drawn by flux
// beside them), its value then handed to the frame's temporal pass; or (3) the world cache,
// which holds it in world space instead, with no screen-space cache (and with `sky`, the sky's
// visibility beside it, a term of its own).
#include "passes/passes.h"

namespace ssgi {

shader::IndirectConstants indirectConstants(const FrameBuild& build, const EffectCache* cache,
                                            const FrameState& frame, VkExtent2D gather) {
    shader::IndirectConstants c{};
    c.rotation = frame.patternRotation;
    c.scale = frame.patternScale;
    c.radius = float(build.settings.indirect_radius);
    c.radialOffset = radialOffset(cache, frame);
    c.visibilityStart = float(build.settings.indirect_visibility_start);
    c.width = int(gather.width);
    c.height = int(gather.height);
    c.cache = cacheConstants(build.settings, cache, frame);
    return c;
}

graph::ImageRef addIndirectLight(FrameBuild& build, const GBufferAndRsm& in, const SkyMaps* sky) {
    if (build.settings.indirect_method == 3) {
        // Held in world space, where the view does not change it: no screen-space cache.
        const FluxVpls vpls = addFluxVplPasses(build, in, build.settings.cache);
        const WorldGrid grid = addWorldVoxelPasses(build);
        const WorldLookups looked = addWorldCachePasses(build, in, vpls, grid, sky);
        build.addCompositeTerm("indirect", looked.indirect);
        if (sky) build.addCompositeTerm("sky-visibility", looked.skyVisibility);
        return looked.indirect;
    }
    // A moved light, or any moved object (whose shadow and RSM moved too), restarts it whole.
    const CachedEffect effect{.name = "indirect",
                              .lightDependent = true,
                              .scalar = false,
                              .motionTest = MOTION_RESTART_ALL};
    const EffectCache* cache =
        createCache(build.graph, build.caches, build.settings, build.size, effect);
    const int method = int(build.settings.indirect_method);
    graph::ImageRef raw;
    if (method == 0) {
        raw = addIndirectPasses(build, in, cache);
    } else {
        std::optional<FluxVpls> vpls;
        if (method == 2) vpls = addFluxVplPasses(build, in, cache != nullptr);
        raw = addInterleavedIndirectPasses(build, in, cache, vpls ? &*vpls : nullptr);
    }
    const graph::ImageRef value = blendInTemporalPass(build, cache, raw);
    build.addCompositeTerm("indirect", value);
    return value;
}

} // namespace ssgi
