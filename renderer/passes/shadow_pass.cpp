// shadow: how much of the spot light's disk each G-buffer pixel sees, from the shadow map: by
// light-space horizons over the map's front and back faces (shadow_variant 1), or by
// percentage-closer filtering with a kernel sized from the disk (0: thesis 3.4, PCSS); cached.
//   reads:  gbuffer.view_depth, gbuffer.normal, shadow_map.depth (rsm.depth where the two are
//           the same size), shadow_map_back.depth (variant 1; and its cache's history, whose
//           values it checks before reusing one while the camera moves)
//   writes: shadow (the fraction of the disk seen, in r; the history's blur in g), shadow.history
#include "passes/passes.h"

namespace ssgi {

graph::ImageRef addShadowPass(FrameBuild& build, const GBufferAndRsm& in) {
    CachedComputePass pass;
    // A moved light restarts it; a moved object, the pixels whose path to the light passes
    // near it. Computed in the light's space, it is the same from any view.
    pass.effect = {.name = "shadow",
                   .lightDependent = true,
                   .scalar = true,
                   .motionTest = MOTION_LIGHT_PATH,
                   .viewIndependent = true};
    pass.shader = "shadow.comp";
    using graph::Use;
    pass.inputs = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"shadowMap", in.shadowMap, Use::Sampled},
                   // Variant 1's back faces; the map itself stands in where they are not drawn.
                   {"shadowMapBack", in.shadowMapBack.valid() ? in.shadowMapBack : in.shadowMap,
                    Use::Sampled}};
    pass.pushSize = sizeof(shader::ShadowConstants);
    pass.bindsHistory = true;
    const Settings& settings = build.settings;
    const auto spec = [&settings](bool restart) {
        const auto samples = [&](double count) {
            return samplesPerFrame(settings, "shadow", int(count), restart);
        };
        return vk::Specialization{{{"TAPS", samples(settings.shadow_taps)},
                                   {"VARIANT", int(settings.shadow_variant)},
                                   {"DIRECTIONS", samples(settings.shadow_directions)},
                                   {"STEPS", int(settings.shadow_steps)}}};
    };
    pass.spec = spec(false);
    pass.restartSpec = spec(true);
    return addCachedComputePass(build, in.gbuffer, std::move(pass),
                                [&build](const CachedRecorder& r) {
                                    shader::ShadowConstants constants{};
                                    constants.rotation = r.frame().patternRotation;
                                    constants.scale = r.frame().patternScale;
                                    constants.normalOffset = float(build.settings.shadow_bias);
                                    constants.radialOffset = r.radialOffset();
                                    r.dispatch(constants);
                                });
}

} // namespace ssgi
