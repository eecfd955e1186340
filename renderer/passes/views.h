// Every debug view, in the order programs list them: the composite's own (VIEW_* of shared.h),
// and one per lighting term, which is also where a term says how it enters the composite's sum
// (TERM_*). A pass that makes a term registers its image under the view's name
// (FrameBuild::addCompositeTerm); a new term is a new row here.
#pragma once

#include "shared.h"

#include <string>

namespace ssgi {

struct ViewDef {
    const char* name;
    int view;             // VIEW_*: VIEW_TERM for a lighting term's view
    int role = TERM_NONE; // a term's role in the composite (TERM_*)
    // A view of another term's image (its view's name), which the pass that makes the term
    // fills with something else for this view (the world cache's cells and their age in the
    // bounce's image); the role says how the composite shows it. Never a term of its own.
    const char* showsTerm = nullptr;
};

inline constexpr ViewDef kViews[] = {
    {"final", VIEW_FINAL},
    {"albedo", VIEW_ALBEDO},
    {"normal", VIEW_NORMAL},
    {"depth", VIEW_DEPTH},
    {"direct", VIEW_DIRECT},
    {"rsm-flux", VIEW_RSM_FLUX},
    {"rsm-normal", VIEW_RSM_NORMAL},
    {"shadow", VIEW_SHADOW},
    {"ao", VIEW_TERM, TERM_SKY_OCCLUSION},
    {"indirect", VIEW_TERM, TERM_IRRADIANCE},
    {"ssdo", VIEW_TERM, TERM_SKY_RADIANCE},
    {"contact", VIEW_CONTACT},
    {"peel", VIEW_PEEL},
    {"sky-visibility", VIEW_TERM, TERM_SKY_FILTER},
    // indirect_method 3: each pixel's own cell's value, unblended, and its state as data (red: no
    // samples; green: its samples' share of world_frames; blue: frames unused over world_lifetime).
    {"world-cells", VIEW_TERM, TERM_IRRADIANCE, "indirect"},
    {"world-age", VIEW_TERM, TERM_SKY_FILTER, "indirect"},
};

// Each of the composite's own views once, and a role for each term's view and no other.
constexpr bool viewsWellFormed() {
    int ownViews = 0;
    for (const ViewDef& v : kViews) {
        if ((v.view == VIEW_TERM) != (v.role != TERM_NONE)) return false;
        if (v.view != VIEW_TERM) {
            if (v.view < 0 || v.view >= VIEW_TERM) return false;
            for (const ViewDef& w : kViews)
                if (&w != &v && w.view == v.view) return false;
            ++ownViews;
        }
    }
    return ownViews == VIEW_TERM;
}
static_assert(viewsWellFormed(), "kViews: every VIEW_* of shared.h once, a role for each term");

// The row of a view's name, or nullptr.
inline const ViewDef* findView(const std::string& name) {
    for (const ViewDef& v : kViews)
        if (name == v.name) return &v;
    return nullptr;
}

} // namespace ssgi
