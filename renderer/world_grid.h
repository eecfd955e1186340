// Where the world cache's voxel grid lies (indirect_method 3; world_voxels_pass.cpp): around the
// scene's geometry inside the light's frustum, the surfaces its VPLs lie on and most of what
// stands between them and the cells that gather them. A grid over the scene's whole bounds
// would spend its voxels on what the light never reaches (the bunny's 20 m floor under a 15 cm
// bunny). The grid is placed again when the light or an object moves.
#pragma once

#include "scene/scene.h"

#include <glm/glm.hpp>
#include <vector>

namespace ssgi {

// The bounds of the parts of the scene's triangles (each instance placed by `transforms`) that
// lie inside the frustum `viewProjection` maps to clip space (x, y in [-w, w], z in [0, w]); an
// empty box when none does.
Aabb boundsInFrustum(const Scene& scene, const std::vector<glm::mat4>& transforms,
                     const glm::mat4& viewProjection);

// A grid of cubic voxels over `box`, `voxels` along its longest side with one more voxel
// beyond each face (so that no surface lies on the grid's edge), at most `voxels` per axis.
struct WorldGridPlacement {
    glm::vec3 origin{0.0f}; // the lowest corner
    float voxel = 1.0f;     // a voxel's side
    glm::ivec3 size{1};     // voxels per axis
};
WorldGridPlacement placeWorldGrid(const Aabb& box, int voxels);

} // namespace ssgi
