// The frame, pass by pass, in order: rasterise the camera's and the light's views; the indirect
// light; the shadow term; ambient occlusion (or the direct light and SSDO in its place); the
// sky's visibility (per pixel, or held in the world cache's cells); the temporal pass that blends
// them all into their histories; the direct light; composite and tonemap. Which passes there are
// follows from the scene's settings; which of them run on a given frame, from the FrameState
// (frame_state.h). docs/frame.md draws the frame this builds.
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
    // consumers read once the temporal pass has blended it; the lighting terms hand theirs to
    // the composite, which adds them up in the order they come here (FrameBuild::addCompositeTerm).
    CompositeImages composite;
    // Depth peeling's second layer serves SSDO's occlusion test, the contact shadows' and the
    // bounce's visibility test.
    if (settings.depth_peeling && (settings.ssdo || settings.contact_shadows ||
                                   (screenSpaceBounce && settings.indirect_visibility)))
        rasterized.secondLayer = addPeelPass(build, rasterized);
    // The sky's maps before the indirect light, whose world cache may hold the sky's visibility
    // in its cells (skyInWorldCache): none to see under a black sky, as in the Cornell boxes.
    std::optional<SkyMaps> skyMaps;
    if (hasSkyVisibility(scene)) skyMaps = addSkyMapsPass(build);
    const bool skyInCells = skyInWorldCache(scene);
    // The indirect light first: its working images are the frame's largest set at once, and the
    // other effects' values, which wait for the temporal pass, are not made yet to add to it.
    if (settings.indirect) addIndirectLight(build, rasterized, skyInCells ? &*skyMaps : nullptr);
    composite.shadow = addShadowPass(build, rasterized);
    if (settings.ssdo) {
        // SSDO's bounce reads the direct light, which reads the blended shadow: a temporal pass
        // of their own blends the effects made so far (the indirect light, the shadow) first.
        addTemporalPass(build, rasterized.gbuffer);
        if (settings.contact_shadows)
            composite.shadow = addContactPass(build, rasterized, composite.shadow);
        composite.direct = addDirectPass(build, rasterized, composite.shadow);
        addSsdoPass(build, rasterized, composite.direct);
    } else if (settings.ao) {
        addAoPass(build, rasterized);
    }
    // The sky's visibility beyond the screen at each pixel, for the sky term beside the AO,
    // where the world cache's cells do not hold it.
    if (skyMaps && !skyInCells) addSkyVisibilityPass(build, rasterized, *skyMaps);
    // One pass blends every cached effect's value of this frame into its history (the frame's
    // only one without SSDO), before anything reads the blended values.
    addTemporalPass(build, rasterized.gbuffer);
    if (settings.contact_shadows && !settings.ssdo)
        composite.shadow = addContactPass(build, rasterized, composite.shadow);
    // Without SSDO only the composite reads the direct light: made once the effects' values are
    // blended, it shares their memory instead of adding to it (FrameGraph's transient images).
    if (!composite.direct.valid())
        composite.direct = addDirectPass(build, rasterized, composite.shadow);
    addCompositePass(build, rasterized, composite);
}

} // namespace ssgi
