// A case's picture (CaseResult::panels): the tested renderer right after the change, its error
// there and at the end (false colour, errorMap()), the region over the converged image and the
// path tracer's image; AO cases compared with the path tracer show the AO with the occluder on
// screen, after it left (fresh and tested) and the path tracer's.
#pragma once

#include "stability/truth.h"

#include <optional>

namespace ssgi::stability::detail {

// Fills res.panels and res.panelNames (its region already taken); `truth`: where the case was
// compared with the path tracer.
void drawPanels(CaseResult& res, const Case& c, const Scene& scene, const TestedRun& tested,
                const FreshRun& fresh, const ConvergedRun& reference,
                const std::optional<TruthImages>& truth);

} // namespace ssgi::stability::detail
