// ao: screen-space ambient occlusion from the G-buffer (thesis 3.2; Mittring; GTAO), cached.
//   reads:  gbuffer.view_depth, gbuffer.normal (and its cache's history)
//   writes: ao (visibility of the hemisphere within the AO radius, 1 = open), ao.history
#include "passes/passes.h"

namespace ssgi {

graph::ImageRef addAoPass(FrameBuild& build, const GBufferAndRsm& in) {
    const Settings& settings = build.settings;
    CachedComputePass pass;
    // A moved object restarts the pixels within the farthest an AO sample reaches (its pattern
    // at its largest); a moved light changes nothing the AO sees.
    pass.effect = {.name = "ao",
                   .lightDependent = false,
                   .scalar = true,
                   .motionTest = MOTION_NEAR_BOX,
                   .motionReach =
                       aoRadius(build.scene) * (1.0f + float(settings.cache_scale_jitter))};
    pass.term = "ao";
    pass.shader = "ao.comp";
    using graph::Use;
    pass.inputs = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled}};
    pass.pushSize = sizeof(shader::AoConstants);
    const auto spec = [&settings](bool restart) {
        const auto samples = [&](double count) {
            return samplesPerFrame(settings, "ao", int(count), restart);
        };
        // The horizon variant's steps place each side's horizon, the highest of them, which no
        // number of frames refines: they stay whole (the other variants average their steps,
        // and the thesis's strata turn with the frame).
        const bool horizon = settings.ao_variant == 2;
        return vk::Specialization{
            {{"VARIANT", int(settings.ao_variant)},
             {"DIRECTIONS", samples(settings.ao_directions)},
             {"STEPS", horizon ? int(settings.ao_steps) : samples(settings.ao_steps)}}};
    };
    pass.spec = spec(false);
    pass.restartSpec = spec(true);
    return addCachedComputePass(build, in.gbuffer, std::move(pass),
                                [&build](const CachedRecorder& r) {
                                    shader::AoConstants constants{};
                                    constants.rotation = r.frame().patternRotation;
                                    constants.scale = r.frame().patternScale;
                                    constants.radius = aoRadius(build.scene);
                                    constants.radialOffset = r.radialOffset();
                                    constants.falloffA = float(build.settings.ao_attenuation_a);
                                    constants.falloffB = float(build.settings.ao_attenuation_b);
                                    r.dispatch(constants);
                                });
}

} // namespace ssgi
