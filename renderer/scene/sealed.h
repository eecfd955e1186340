// A light sealed off from the camera by a closed surface: the light's disk on one side of it,
// every camera ray's start on the other. No path then joins the light to the camera (surfaces
// are opaque: a path that crosses the surface is blocked), so nothing the camera sees is lit by
// the light, directly or by any bounce; the path tracer's image of it is black but for the sky.
// The real-time frame would light it: the reflective shadow map's virtual lights, the shadow
// maps' horizons and the receiver planes of PCF do not know inside from outside, and the
// frame's light is turned off in its place (renderer.cpp). docs/robustness.md.
#pragma once

#include "scene/scene.h"

#include <optional>
#include <string>
#include <vector>

namespace ssgi {

// The instance whose closed surface separates the light from the camera.
struct Seal {
    std::string object; // the instance's name ("instance N" where it has none)
    bool lightInside = true; // the light inside the surface and the camera outside, or the reverse
};

// The scene's closed surfaces and the seal they make between a light and a camera.
//
// A closed surface is one mesh whose triangles, with vertices closer than 1e-6 of the mesh's
// bounding-box diagonal taken as one (a sphere's seam and bottom pole are computed apart by
// float rounding), run each edge once each way: every edge shared by exactly two triangles that
// agree on the side they face. Its material has no alpha mask (a cut-out is a hole). The
// generalized winding number of a point off such a surface (the solid angles of its triangles
// seen from the point, over 4 pi) is an integer, constant between crossings of the surface: two
// points of different winding numbers lie on two sides of it. A mesh is checked once, the first
// time a light or camera stands within its bounding box (most never are).
//
// What is tested is exact but conservative: the light's disk (a ball of its radius around its
// position) and the camera's rays' starts (a ball around the camera's position that holds its
// near plane's rectangle) must each keep clear of every triangle of the surface; a ball that
// touches it is not decided, and nothing is sealed. Surfaces closed only together (a box of
// six quads, a mesh split in two glTF primitives) are not seen as closed.
class LightSeals {
public:
    // `scene` must outlive this. Its meshes' boxes are found here (one pass over the vertices);
    // whether a mesh is closed, the first time find() needs it.
    explicit LightSeals(const Scene& scene);

    // The instance (placed by `transforms`, one per instance) whose closed surface has `light` on
    // one side and `camera`, seen at `aspect` (width / height), on the other; none where no
    // closed surface does. A surface whose box holds neither costs a box test; one whose box
    // holds either, a pass over its triangles. Not for two threads at once.
    std::optional<Seal> find(const SpotLight& light, const Camera& camera, float aspect,
                             const std::vector<glm::mat4>& transforms) const;

private:
    bool closed(size_t mesh) const; // computed on first use

    const Scene& scene_;
    mutable std::vector<int8_t> closed_; // per mesh: -1 not yet known, 0 open, 1 closed
    std::vector<Aabb> boxes_;            // per mesh, in its own space
};

// What the programs say of a seal: "the light ... inside the closed mesh 'tall block' ...".
std::string sealWarning(const Seal& seal);

} // namespace ssgi
