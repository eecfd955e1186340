// The scripted cases of the stability suite: where screen-space methods and temporal caches are
// known to fail, each a scene file in scenes/stability/ with a camera path, plus what the scene
// file cannot say (a light path, a resize, the region to measure). Moving objects are the scene
// file's object paths, played along the same time as the camera path.
#pragma once

#include "scene/scene.h"

#include <string>
#include <vector>

namespace ssgi::stability {

// The pixels a case's error is measured in, taken at the final camera.
enum class Region {
    Disoccluded,   // surfaces the first camera did not see (revealed from behind an occluder)
    Carried,       // pixels whose history the renderer kept across the last change (a cut)
    Thin,          // thin geometry and the background right beside it
    NearOccluder,  // receivers of an occluder's occlusion (Case::occluder)
    LightChanged,  // where the moved light changed the converged image
    ObjectChanged, // where the moved object changed the converged image
    Grazing,       // surfaces seen at a grazing angle
    DepthEdges,    // both sides of depth discontinuities (halos)
    Geometry,      // every pixel with geometry
};

inline const char* regionName(Region r) {
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

// What the path-traced reference is compared with: the final image ("hdr", mode Full), the
// AO alone ("ao.history", mode Ao; for a scene whose AO has no distance falloff), or nothing.
enum class Truth { None, Full, Ao };

struct Case {
    std::string name;    // as the command line names it
    std::string scene;   // relative to the repository
    std::string failure; // what goes wrong there, one line
    Region region = Region::Geometry;
    Truth truth = Truth::Full;
    uint32_t pathFrames = 8; // frames along the camera path, after the warm-up
    // A moving light: over the path frames it slides from the scene file's position to
    // `lightTo`, aimed at `lightAim` all the way.
    bool movesLight = false;
    glm::vec3 lightTo{0.0f}, lightAim{0.0f};
    // A window resize halfway along the path: a new renderer, `resizeScale` times the size.
    float resizeScale = 0.0f;
    Aabb occluder; // for Region::NearOccluder
};

inline std::vector<Case> suite() {
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
    Case* resize = add("resize", "resize.json",
                       "a window resize mid-path: every history is lost at once", Region::Geometry);
    resize->resizeScale = 0.75f;
    return cases;
}

// The case named `name`; InputError naming the known cases otherwise.
inline Case findCase(const std::string& name) {
    std::string known;
    for (const Case& c : suite()) {
        if (c.name == name) return c;
        known += " " + c.name;
    }
    throw InputError("unknown case '" + name + "' (cases:" + known + ")");
}

} // namespace ssgi::stability
