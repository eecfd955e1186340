#include "scene/sealed.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

namespace ssgi {

namespace {

// A ball that must keep clear of a surface: the light's disk, the camera's rays' starts.
struct Ball {
    glm::dvec3 center;
    double radius;
};

bool ballMeetsBox(const Ball& ball, const Aabb& box) {
    const glm::dvec3 nearest = glm::clamp(ball.center, glm::dvec3(box.min), glm::dvec3(box.max));
    return glm::distance(nearest, ball.center) <= ball.radius;
}

// The point of triangle abc nearest to p (the regions of the triangle's Voronoi diagram: its
// vertices, its edges, its face).
glm::dvec3 nearestOnTriangle(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denominator = 1.0 / (va + vb + vc);
    return a + ab * (vb * denominator) + ac * (vc * denominator);
}

// The solid angle of triangle abc seen from the origin, signed by the side it faces
// (Van Oosterom and Strackee's formula).
double solidAngle(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double numerator = glm::dot(a, glm::cross(b, c));
    const double denominator =
        la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
    return 2.0 * std::atan2(numerator, denominator);
}

// Where each ball lies with respect to one placed closed surface: its winding number, or none
// where the ball comes within 1e-6 of the surface's diagonal of it (a margin of rounding, the
// path tracer's and the rasteriser's).
std::vector<std::optional<long>> windingNumbers(const Mesh& mesh, const glm::mat4& transform,
                                                const std::vector<Ball>& balls) {
    const glm::dmat4 m(transform);
    std::vector<glm::dvec3> world(mesh.vertices.size());
    glm::dvec3 low(HUGE_VAL), high(-HUGE_VAL);
    for (size_t i = 0; i < world.size(); ++i) {
        world[i] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.vertices[i].position), 1.0));
        low = glm::min(low, world[i]);
        high = glm::max(high, world[i]);
    }
    const double margin = 1e-6 * glm::distance(low, high);
    std::vector<std::optional<long>> result(balls.size());
    for (size_t k = 0; k < balls.size(); ++k) {
        const Ball& ball = balls[k];
        double sum = 0.0, nearest = HUGE_VAL;
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const glm::dvec3 a = world[mesh.indices[t]], b = world[mesh.indices[t + 1]],
                             c = world[mesh.indices[t + 2]];
            nearest = std::min(nearest,
                               glm::distance(nearestOnTriangle(ball.center, a, b, c), ball.center));
            sum += solidAngle(a - ball.center, b - ball.center, c - ball.center);
        }
        const double w = sum / (4.0 * glm::pi<double>());
        // Off the surface w is an integer up to rounding; anything else is no closed surface.
        if (nearest > ball.radius + margin && std::abs(w - std::round(w)) < 0.01)
            result[k] = std::lround(w);
    }
    return result;
}

// How far the camera's rays start from its position: the corners of its near plane (the
// rasteriser's and the path tracer's, camera.h).
double nearPlaneReach(const Camera& camera, float aspect) {
    const double t = std::tan(0.5 * double(camera.yfov));
    return double(camera.znear) * std::sqrt(1.0 + t * t * (1.0 + double(aspect) * aspect));
}

} // namespace

LightSeals::LightSeals(const Scene& scene)
    : scene_(scene), closed_(scene.meshes.size(), -1), boxes_(scene.meshes.size()) {
    for (size_t m = 0; m < scene.meshes.size(); ++m)
        for (const Vertex& v : scene.meshes[m].vertices)
            boxes_[m].extend(v.position);
}

bool LightSeals::closed(size_t meshIndex) const {
    if (closed_[meshIndex] >= 0) return closed_[meshIndex] == 1;
    const Mesh& mesh = scene_.meshes[meshIndex];
    const Material* material = mesh.material >= 0 && size_t(mesh.material) < scene_.materials.size()
                                   ? &scene_.materials[size_t(mesh.material)]
                                   : nullptr;
    bool isClosed = !mesh.indices.empty() && mesh.indices.size() % 3 == 0 &&
                    !(material && material->alphaMask);
    if (isClosed) {
        // Vertices within `tolerance` of each other are one. Each is looked for in its cell of
        // 1024 times that size, and in a neighbouring cell only where it lies within
        // `tolerance` of the border between them (rarely: a cell is looked up about once).
        Aabb box;
        for (const Vertex& v : mesh.vertices)
            box.extend(v.position);
        const double tolerance = std::max(1e-6 * double(glm::length(box.size())), 1e-30);
        const double cellSize = 1024.0 * tolerance;
        auto key = [](glm::i64vec3 c) {
            return uint64_t(c.x) * 0x9E3779B97F4A7C15ull ^ uint64_t(c.y) * 0xC2B2AE3D27D4EB4Full ^
                   uint64_t(c.z) * 0x165667B19E3779F9ull;
        };
        std::unordered_multimap<uint64_t, uint32_t> cells;
        cells.reserve(mesh.vertices.size());
        std::vector<uint32_t> welded(mesh.vertices.size());
        for (uint32_t i = 0; i < mesh.vertices.size(); ++i) {
            const glm::dvec3 p(mesh.vertices[i].position);
            const glm::dvec3 at = (p - glm::dvec3(box.min)) / cellSize;
            const glm::i64vec3 cell(glm::floor(at));
            glm::i64vec3 low(0), high(0); // the neighbours to look in, per axis
            for (int axis = 0; axis < 3; ++axis) {
                const double within = (at[axis] - double(cell[axis])) * cellSize;
                low[axis] = within < tolerance ? -1 : 0;
                high[axis] = cellSize - within < tolerance ? 1 : 0;
            }
            welded[i] = i;
            for (int64_t dz = low.z; dz <= high.z && welded[i] == i; ++dz)
                for (int64_t dy = low.y; dy <= high.y && welded[i] == i; ++dy)
                    for (int64_t dx = low.x; dx <= high.x && welded[i] == i; ++dx) {
                        const auto [first, last] =
                            cells.equal_range(key(cell + glm::i64vec3(dx, dy, dz)));
                        for (auto it = first; it != last; ++it)
                            if (glm::distance(glm::dvec3(mesh.vertices[it->second].position), p) <=
                                tolerance) {
                                welded[i] = it->second;
                                break;
                            }
                    }
            if (welded[i] == i) cells.emplace(key(cell), i);
        }
        // Every directed edge once, and its reverse once: each edge shared by two triangles
        // that run it opposite ways. Triangles that welding collapsed have no area: left out.
        std::vector<uint64_t> edges;
        edges.reserve(mesh.indices.size());
        for (size_t t = 0; t < mesh.indices.size() && isClosed; t += 3) {
            uint32_t v[3];
            for (int k = 0; k < 3; ++k) {
                if (mesh.indices[t + k] >= welded.size()) isClosed = false;
                else v[k] = welded[mesh.indices[t + k]];
            }
            if (!isClosed || v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
            for (int k = 0; k < 3; ++k)
                edges.push_back(uint64_t(v[k]) << 32 | v[(k + 1) % 3]);
        }
        std::sort(edges.begin(), edges.end());
        isClosed = isClosed && !edges.empty() &&
                   std::adjacent_find(edges.begin(), edges.end()) == edges.end();
        for (size_t i = 0; i < edges.size() && isClosed; ++i) {
            const uint64_t reverse = edges[i] << 32 | edges[i] >> 32;
            isClosed = std::binary_search(edges.begin(), edges.end(), reverse);
        }
    }
    closed_[meshIndex] = isClosed ? 1 : 0;
    return isClosed;
}

std::optional<Seal> LightSeals::find(const SpotLight& light, const Camera& camera, float aspect,
                                     const std::vector<glm::mat4>& transforms) const {
    const std::vector<Ball> balls = {
        {glm::dvec3(light.position), double(light.radius)},
        {glm::dvec3(camera.position), nearPlaneReach(camera, aspect)}};
    for (size_t i = 0; i < scene_.instances.size() && i < transforms.size(); ++i) {
        const Instance& instance = scene_.instances[i];
        // The mesh's box placed: its corners' box, which holds the placed mesh.
        const Aabb& local = boxes_[size_t(instance.mesh)];
        if (local.empty()) continue;
        Aabb box;
        for (int corner = 0; corner < 8; ++corner)
            box.extend(glm::vec3(transforms[i] *
                                 glm::vec4(corner & 1 ? local.max.x : local.min.x,
                                           corner & 2 ? local.max.y : local.min.y,
                                           corner & 4 ? local.max.z : local.min.z, 1.0f)));
        const Aabb wider{box.min - 1e-4f * glm::length(box.size()),
                         box.max + 1e-4f * glm::length(box.size())};
        // Outside its box, a ball is outside the surface: winding number 0 for both.
        if (!ballMeetsBox(balls[0], wider) && !ballMeetsBox(balls[1], wider)) continue;
        if (!closed(size_t(instance.mesh))) continue;
        const auto w = windingNumbers(scene_.meshes[size_t(instance.mesh)], transforms[i], balls);
        if (!w[0] || !w[1] || *w[0] == *w[1]) continue;
        return Seal{instance.name.empty() ? "instance " + std::to_string(i) : instance.name,
                    *w[0] != 0};
    }
    return std::nullopt;
}

std::string sealWarning(const Seal& seal) {
    return std::string("the light is ") + (seal.lightInside ? "inside" : "outside") +
           " the closed mesh '" + seal.object + "' and the camera " +
           (seal.lightInside ? "outside" : "inside") +
           " it: no light reaches what the camera sees, which is black but for the sky (the "
           "light's position or the mesh's may be wrong)";
}

} // namespace ssgi
