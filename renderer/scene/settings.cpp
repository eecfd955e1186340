// Settings whose defaults derive from the scene's own size, so a scene file names only what
// differs and one default serves every scale.
#include "scene/scene.h"

#include <glm/glm.hpp>

namespace ssgi {

float aoRadius(const Scene& scene) {
    const double derived = 0.05 * glm::length(scene.bounds.size());
    return float(scene.setting("ao_radius", derived > 0.0 ? derived : 0.1));
}

} // namespace ssgi
