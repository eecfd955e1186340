// ssdo: screen-space directional occlusion of the sky plus one bounce of the direct-lit frame
// (Ritschel et al. 2009), cached; replaces sky x AO in the composite when on.
//   reads:  gbuffer.view_depth, .normal, .albedo, direct, peel.position with depth peeling (and
//           its cache's history)
//   writes: ssdo (radiance), ssdo.history
#include "passes/passes.h"

namespace ssgi {

graph::ImageRef addSsdoPass(FrameBuild& build, const GBufferAndRsm& in, graph::ImageRef direct) {
    const Settings& settings = build.settings;
    const float rMax =
        settings.ssdo_radius > 0.0 ? float(settings.ssdo_radius) : aoRadius(build.scene);
    CachedComputePass pass;
    // Its bounce carries the direct light: a moved light, or any moved object (whose shadow
    // moved too), restarts it whole.
    pass.effect = {
        .name = "ssdo", .lightDependent = true, .scalar = false, .motionTest = MOTION_RESTART_ALL};
    pass.term = "ssdo";
    pass.shader = "ssdo.comp";
    using graph::Use;
    pass.inputs = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"gbufferAlbedo", in.gbuffer.albedo, Use::Sampled},
                   {"directRadiance", direct, Use::Sampled},
                   secondLayerInput(in)};
    pass.pushSize = sizeof(shader::SsdoConstants);
    const auto spec = [&settings, &in](bool restart) {
        return vk::Specialization{
            {{"SAMPLES", samplesPerFrame(settings, "ssdo", int(settings.ssdo_samples), restart)},
             {"PEELING", in.secondLayer.valid() ? 1 : 0}}};
    };
    pass.spec = spec(false);
    pass.restartSpec = spec(true);
    return addCachedComputePass(build, in.gbuffer, std::move(pass),
                                [&build, rMax](const CachedRecorder& r) {
                                    shader::SsdoConstants constants{};
                                    constants.rotation = r.frame().patternRotation;
                                    constants.scale = r.frame().patternScale;
                                    constants.rMax = rMax;
                                    constants.bounceStrength = float(build.settings.ssdo_bounce);
                                    r.dispatch(constants);
                                });
}

} // namespace ssgi
