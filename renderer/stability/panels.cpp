// The panels of panels.h.

#include "stability/panels.h"

#include "shared.h"

namespace ssgi::stability::detail {

namespace {

// Linear radiance as the composite pass shows it (shared.h): exposure, ACES fit, sRGB.
Pixels tonemapped(const Pixels& hdr, float exposure) {
    Pixels out(hdr.size(), 1.0f);
    for (size_t i = 0; i < hdr.size(); i += 4)
        for (size_t c = 0; c < 3; ++c)
            out[i + c] = shader::encodeSrgb(shader::tonemapAces(hdr[i + c] * exposure));
    return out;
}

// An AO image (R) as display grey, its occlusion tripled so that a faint one shows.
Pixels grey(const Pixels& ao) {
    Pixels out(ao.size(), 1.0f);
    for (size_t i = 0; i < ao.size(); i += 4)
        out[i] = out[i + 1] = out[i + 2] = std::clamp(1.0f - 3.0f * (1.0f - ao[i]), 0.0f, 1.0f);
    return out;
}

// The region tinted magenta over a display image.
Pixels regionOverlay(const Pixels& ldr, const Mask& region) {
    Pixels overlay = ldr;
    for (size_t i = 0; i < region.size(); ++i)
        if (region[i])
            for (size_t ch = 0; ch < 3; ++ch)
                overlay[4 * i + ch] = 0.4f * overlay[4 * i + ch] + (ch == 1 ? 0.0f : 0.6f);
    return overlay;
}

} // namespace

void drawPanels(CaseResult& res, const Case& c, const Scene& scene, const TestedRun& tested,
                const FreshRun& fresh, const ConvergedRun& reference,
                const std::optional<TruthImages>& truth) {
    if (truth && c.truth == Truth::Ao) {
        res.panels = {grey(tested.startAo), grey(truth->start), grey(fresh.ao), grey(tested.endAo),
                      grey(truth->end)};
        res.panelNames = {"AO, occluder on screen", "path-traced", "AO, occluder gone (fresh)",
                          "(tested)", "path-traced"};
        return;
    }
    const metrics::Image target{res.width, res.height, reference.view.hdr};
    auto errorPanel = [&](const Pixels& image) {
        return metrics::errorMap({res.width, res.height, image}, target);
    };
    res.panels = {tested.changeLdr, errorPanel(tested.after.front()),
                  errorPanel(tested.after.back()), regionOverlay(reference.ldr, res.region)};
    res.panelNames = {"tested, at the change", "its error there", "its error at the end", "region"};
    if (truth) {
        res.panels.push_back(tonemapped(truth->end, float(scene.settings.exposure)));
        res.panelNames.push_back("path-traced");
    }
}

} // namespace ssgi::stability::detail
