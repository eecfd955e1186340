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
    rasterized.shadowMap = addShadowMapPass(build, rasterized.rsm);
    if (settings.shadow_variant == 1 && settings.shadow_taps > 1)
        rasterized.shadowMapBack = addShadowMapBackPass(build);
    // The screen-space visibility test's inputs; the world cache (indirect_method 3) tests its
    // VPLs in a voxel grid instead.
    const bool screenSpaceBounce = settings.indirect && settings.indirect_method != 3;
    if (screenSpaceBounce && settings.indirect_visibility && settings.indirect_visibility_light)
        rasterized.lightDepthMin = addLightDepthMinPass(build, rasterized.rsm);
    addReprojectionPass(build, rasterized.gbuffer);
    // Each cached effect returns its blended history (cached_effect_pass.h), which is what its
    // consumers read; the lighting terms hand theirs to the composite, which adds them up in the
    // order they come here (FrameBuild::addCompositeTerm).
    CompositeImages composite;
    composite.shadow = addShadowPass(build, rasterized);
    // Depth peeling's second layer serves SSDO's occlusion test, the contact shadows' and the
    // bounce's visibility test.
    if (settings.depth_peeling && (settings.ssdo || settings.contact_shadows ||
                                   (screenSpaceBounce && settings.indirect_visibility)))
        rasterized.secondLayer = addPeelPass(build, rasterized);
    if (settings.contact_shadows)
        composite.shadow = addContactPass(build, rasterized, composite.shadow);
    if (settings.ssdo) {
        // SSDO's bounce reads the direct light.
        composite.direct = addDirectPass(build, rasterized, composite.shadow);
        addSsdoPass(build, rasterized, composite.direct);
    } else if (settings.ao) {
        addAoPass(build, rasterized);
    }
    if (settings.indirect) addIndirectLight(build, rasterized);
    // Without SSDO only the composite reads the direct light: made once the indirect light's
    // working images are gone, it shares their memory instead of adding to it (FrameGraph's
    // transient images).
    if (!composite.direct.valid())
        composite.direct = addDirectPass(build, rasterized, composite.shadow);
    // The sky's visibility beyond the screen, for the sky term beside the AO (none to see
    // under a black sky, as in the Cornell boxes).
    if (hasSkyVisibility(scene)) addSkyVisibilityPasses(build, rasterized);
    addCompositePass(build, rasterized, composite);
}

} // namespace ssgi
