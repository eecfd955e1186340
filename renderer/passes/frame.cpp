// The frame, pass by pass, in order: rasterise the camera's and the light's views; the shadow
// term; ambient occlusion (or the direct light and SSDO in its place); the indirect light; the
// direct light; the sky's visibility; composite and tonemap. Which passes there are follows from
// the scene's settings; which of them run on a given frame, from the FrameState (frame_state.h).
// docs/frame.md draws the frame this builds.
#include "passes/passes.h"

namespace ssgi {

void addFramePasses(FrameBuild& build) {
    const Scene& scene = build.scene;
    const Settings& settings = build.settings;
    GBufferAndRsm rasterized;
    rasterized.gbuffer = addGBufferPass(build);
    rasterized.rsm = addRsmPass(build);
    if (settings.cache) addReprojectionPass(build, rasterized.gbuffer);
    // Each cached effect returns its blended history (cached_effect_pass.h), which is what its
    // consumers read.
    LightingTerms terms;
    terms.shadow = addShadowPass(build, rasterized);
    // Depth peeling's second layer serves SSDO's occlusion test and the contact shadows'.
    if (settings.depth_peeling && (settings.ssdo || settings.contact_shadows))
        terms.secondLayer = addPeelPass(build, rasterized);
    if (settings.contact_shadows)
        terms.shadow = addContactPass(build, rasterized, terms.shadow, terms.secondLayer);
    if (settings.ssdo) {
        terms.direct = addDirectPass(build, rasterized, terms.shadow); // SSDO's bounce reads it
        terms.ssdo = addSsdoPass(build, rasterized, terms.direct, terms.secondLayer);
    } else if (settings.ao) {
        terms.ao = addAoPass(build, rasterized);
    }
    if (settings.indirect) terms.indirect = addIndirectLight(build, rasterized);
    // Without SSDO only the composite reads the direct light: made once the indirect light's
    // working images are gone, it shares their memory instead of adding to it (FrameGraph's
    // transient images).
    if (!terms.direct.valid()) terms.direct = addDirectPass(build, rasterized, terms.shadow);
    // The sky's visibility beyond the screen, for the sky term beside the AO (none to see
    // under a black sky, as in the Cornell boxes).
    const bool blackSky = scene.sky.zenith == glm::vec3(0.0f) &&
                          scene.sky.horizon == glm::vec3(0.0f) &&
                          scene.sky.ground == glm::vec3(0.0f);
    if (settings.sky_visibility && !settings.ssdo && !blackSky)
        terms.skyVisibility = addSkyVisibilityPasses(build, rasterized);
    addCompositePass(build, rasterized, terms);
}

} // namespace ssgi
