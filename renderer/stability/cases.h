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

const char* regionName(Region r);

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
    // A window resize as the camera stops (the hold's first frame): a renderer `resizeScale`
    // times the size that goes on from the old one (Renderer::continueFrom).
    float resizeScale = 0.0f;
    Aabb occluder; // for Region::NearOccluder
};

std::vector<Case> suite();

// The case named `name`; InputError naming the known cases otherwise.
Case findCase(const std::string& name);

} // namespace ssgi::stability
