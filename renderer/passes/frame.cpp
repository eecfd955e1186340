// The frame, pass by pass, in order: rasterise the camera's and the light's views; the shadow
// term; ambient occlusion (or the direct light and SSDO in its place); the indirect light
// (interleaved VPL subsets and their filter, or the thesis's half-resolution gather and its
// upsampling); the direct light; the sky's visibility; composite and tonemap. Which passes there
// are follows from the scene's settings; docs/frame.md draws the frame this builds.
#include "passes/pass_setup.h"

namespace ssgi {

void addFramePasses(PassSetup& s) {
    const Scene& model = s.model;
    const Settings& m = model.settings;
    GBufferAndRsm scenes;
    scenes.gbuffer = addGBufferPass(s);
    scenes.rsm = addRsmPass(s);
    // Each cached effect: its pass computes what is not converged, its temporal pass blends
    // that into the history, and the consumers read the blended value.
    LightingTerms terms;
    EffectCache* shadowCache =
        createCache(s, "shadow", {m.cache_shadow, m.cache_tile_shadow, m.cache_blur_shadow},
                    {.lightDependent = true, .scalar = true});
    if (shadowCache) shadowCache->motionTest = MOTION_LIGHT_PATH;
    terms.shadow = addTemporalPass(s, shadowCache, addShadowPass(s, scenes, shadowCache), scenes);
    // Depth peeling's second layer serves SSDO's occlusion test and the contact shadows'.
    if (m.depth_peeling && (m.ssdo || m.contact_shadows))
        terms.secondLayer = addPeelPass(s, scenes);
    if (m.contact_shadows)
        terms.shadow = addContactPass(s, scenes, terms.shadow, terms.secondLayer);
    if (m.ssdo) {
        terms.direct = addDirectPass(s, scenes, terms.shadow); // SSDO's bounce reads it
        EffectCache* cache =
            createCache(s, "ssdo", {m.cache_ssdo, m.cache_tile_ssdo, m.cache_blur_ssdo},
                        {.lightDependent = true, .scalar = false});
        terms.ssdo = addTemporalPass(
            s, cache, addSsdoPass(s, scenes, terms.direct, terms.secondLayer, cache), scenes);
    } else if (m.ao) {
        EffectCache* cache = createCache(s, "ao", {m.cache_ao, m.cache_tile_ao, m.cache_blur_ao},
                                         {.lightDependent = false, .scalar = true});
        if (cache) { // the farthest an AO sample reaches, its pattern at its largest
            cache->motionTest = MOTION_NEAR_BOX;
            cache->motionReach = aoRadius(model) * (1.0f + float(m.cache_scale_jitter));
        }
        terms.ao = addTemporalPass(s, cache, addAoPass(s, scenes, cache), scenes);
    }
    if (m.indirect) {
        EffectCache* cache = createCache(
            s, "indirect", {m.cache_indirect, m.cache_tile_indirect, m.cache_blur_indirect},
            {.lightDependent = true, .scalar = false});
        std::optional<FluxVpls> vpls;
        if (m.indirect_method == 2) vpls = addFluxVplPasses(s, scenes, cache);
        const graph::ImageRef indirect =
            m.indirect_method >= 1
                ? addInterleavedIndirectPasses(s, scenes, cache, vpls ? &*vpls : nullptr)
                : addIndirectPasses(s, scenes, cache);
        terms.indirect = addTemporalPass(s, cache, indirect, scenes);
    }
    // Without SSDO only the composite reads the direct light: made once the indirect light's
    // working images are gone, it shares their memory instead of adding to it (FrameGraph's
    // transient images).
    if (!terms.direct.valid()) terms.direct = addDirectPass(s, scenes, terms.shadow);
    // The sky's visibility beyond the screen, for the sky term beside the AO (none to see
    // under a black sky, as in the Cornell boxes).
    const bool blackSky = model.sky.zenith == glm::vec3(0.0f) &&
                          model.sky.horizon == glm::vec3(0.0f) &&
                          model.sky.ground == glm::vec3(0.0f);
    if (m.sky_visibility && !m.ssdo && !blackSky)
        terms.skyVisibility = addSkyVisibilityPasses(s, scenes);
    addCompositePass(s, scenes, terms);
}

} // namespace ssgi
