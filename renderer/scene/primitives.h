// Procedural meshes for scene files: a Cornell box or a floor under a scanned model should be a
// few lines of text, not a mesh file. Geometry is generated directly in world space, so each
// mesh's Instance has the identity transform.
#pragma once

#include "scene/scene.h"

#include <array>

namespace ssgi {

// Two triangles (0,1,2), (0,2,3); the flat normal faces the side from which the corners run
// counter-clockwise. The caller rejects degenerate quads (quadNormal() of zero length).
Mesh makeQuad(const std::array<glm::vec3, 4>& corners, int material);
// Unit length; zero when the quad has no area.
glm::vec3 quadNormal(const std::array<glm::vec3, 4>& corners);

// 6 faces of 4 vertices each (flat outward normals), rotated about +Y through its centre.
Mesh makeBox(glm::vec3 center, glm::vec3 size, float rotateYDegrees, int material);

// A UV sphere: `segments` around the axis, segments/2 from pole to pole, smooth normals.
Mesh makeSphere(glm::vec3 center, float radius, int segments, int material);

} // namespace ssgi
