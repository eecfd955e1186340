#include "stability/cases.h"

namespace ssgi::stability {

const char* regionName(Region r) {
    switch (r) {
    case Region::Disoccluded:
        return "disoccluded";
    case Region::Carried:
        return "history kept at the cut";
    case Region::Thin:
        return "thin geometry";
    case Region::NearOccluder:
        return "near the occluder";
    case Region::LightChanged:
        return "changed by the light";
    case Region::ObjectChanged:
        return "changed by the object";
    case Region::Grazing:
        return "grazing angles";
    case Region::DepthEdges:
        return "depth edges";
    case Region::Geometry:
        return "all geometry";
    }
    return "?";
}

std::vector<Case> suite() {
    std::vector<Case> cases;
    auto add = [&](std::string name, std::string file, std::string failure, Region region) {
        Case& c = cases.emplace_back();
        c.name = std::move(name);
        c.scene = "scenes/stability/" + file;
        c.failure = std::move(failure);
        c.region = region;
        return &c;
    };
    add("pillar", "pillar.json",
        "disocclusion: the wall behind a pillar has no history when it is revealed",
        Region::Disoccluded);
    add("thin-chairs", "thin-chairs.json",
        "thin geometry: chair legs and frames fail the reprojection test as they move",
        Region::Thin);
    add("thin-pine", "thin-pine.json", "thin geometry: alpha-masked needles in front of the sky",
        Region::Thin);
    Case* edge = add("screen-edge", "screen-edge.json",
                     "an occluder leaving the screen takes its screen-space occlusion with it",
                     Region::NearOccluder);
    edge->truth = Truth::Ao;
    edge->occluder.extend({-0.25f, 0.0f, -0.25f});
    edge->occluder.extend({0.25f, 2.5f, 0.25f});
    Case* light =
        add("moving-light", "moving-light.json",
            "a moving light invalidates the cached shadow and bounce light", Region::LightChanged);
    light->movesLight = true;
    light->lightTo = {0.12f, 0.5478f, 0.2f};
    light->lightAim = {0.2f, 0.0f, 0.25f};
    add("moving-object", "moving-object.json",
        "a moving object (the thesis's stated limit): its old shadow and occlusion go stale",
        Region::ObjectChanged);
    add("grazing", "grazing.json",
        "grazing angles: long pixel footprints for the reprojection test and screen-space samples",
        Region::Grazing);
    add("halos", "halos.json",
        "depth discontinuities: occlusion and resampled history spill across silhouettes",
        Region::DepthEdges);
    add("cut", "cut.json",
        "a camera cut: history survives only where reprojection proves the same surface",
        Region::Carried);
    Case* resize =
        add("resize", "resize.json",
            "a window resize as the camera stops: every history at another size", Region::Geometry);
    resize->resizeScale = 0.75f;
    // The same window resize with the camera still and every history converged: the motion
    // before `resize` restarts most histories anyway, so only here does a resize that dropped
    // them, or blurred them into starting over, show (excessOverUnresized).
    Case* still = add("resize-still", "resize.json",
                      "a window resize on a still camera: every converged history at another size",
                      Region::Geometry);
    still->resizeScale = 0.75f;
    still->pathFrames = 0;
    return cases;
}

Case findCase(const std::string& name) {
    std::string known;
    for (const Case& c : suite()) {
        if (c.name == name) return c;
        known += " " + c.name;
    }
    throw InputError("unknown case '" + name + "' (cases:" + known + ")");
}

} // namespace ssgi::stability
