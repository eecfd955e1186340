#include "reference/ray_scene.h"

#include "reference/surface_texture.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace ssgi::reference {

struct RayScene::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    ~Embree() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

glm::vec2 interpolatedUv(const RayScene::Geometry& g, unsigned prim, float u, float v) {
    const uint32_t* tri = &g.indices[3 * size_t(prim)];
    return (1.0f - u - v) * g.uvs[tri[0]] + u * g.uvs[tri[1]] + v * g.uvs[tri[2]];
}

// The vertex colour at a hit, exactly 1 where the mesh has none.
glm::vec4 interpolatedColor(const RayScene::Geometry& g, unsigned prim, float u, float v) {
    if (g.colors.empty()) return glm::vec4(1.0f);
    const uint32_t* tri = &g.indices[3 * size_t(prim)];
    return (1.0f - u - v) * g.colors[tri[0]] + u * g.colors[tri[1]] + v * g.colors[tri[2]];
}

// Embree calls this for every candidate hit on an alpha-masked geometry; rejecting the hit
// makes the traversal continue behind it, for the nearest-hit and the any-hit query alike.
void alphaMaskFilter(const RTCFilterFunctionNArguments* args) {
    const auto* g = static_cast<const RayScene::Geometry*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
        if (maskedOut(*g->material, g->texture, interpolatedUv(*g, prim, u, v),
                      interpolatedColor(*g, prim, u, v)))
            args->valid[i] = 0;
    }
}

void reportEmbreeError(void*, RTCError code, const char* message) {
    // Errors surface through rtcGetDeviceError after each call that matters; this only keeps
    // Embree from printing on its own.
    (void)code;
    (void)message;
}

std::unique_ptr<RayScene::Geometry> bake(const Scene& scene, const Instance& instance) {
    const Mesh& mesh = scene.meshes.at(size_t(instance.mesh));
    auto g = std::make_unique<RayScene::Geometry>();
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(instance.transform)));
    for (const Vertex& v : mesh.vertices) {
        g->positions.push_back(glm::vec3(instance.transform * glm::vec4(v.position, 1.0f)));
        g->normals.push_back(normalMatrix * v.normal); // normalised after interpolation
        g->uvs.push_back(v.uv);
        if (mesh.vertexColors) g->colors.push_back(glm::vec4(v.color) / 65535.0f);
    }
    if (mesh.indices.empty()) {
        for (uint32_t i = 0; i + 2 < uint32_t(mesh.vertices.size()); i += 3)
            g->indices.insert(g->indices.end(), {i, i + 1, i + 2});
    } else {
        const size_t whole = mesh.indices.size() / 3 * 3;
        g->indices.assign(mesh.indices.begin(), mesh.indices.begin() + long(whole));
    }
    // The loaders check this; a scene built in code might not, and Embree would read past
    // the vertex buffer.
    for (uint32_t index : g->indices)
        if (index >= mesh.vertices.size())
            throw InputError(scene.sourcePath + ": mesh " + std::to_string(instance.mesh) +
                             " has vertex index " + std::to_string(index) + " of " +
                             std::to_string(mesh.vertices.size()) + " vertices");
    g->material = &scene.materials.at(size_t(mesh.material));
    if (g->material->baseColorTexture >= 0)
        g->texture = &scene.textures.at(size_t(g->material->baseColorTexture));
    return g;
}

void checkDevice(RTCDevice device, const char* what) {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                                 std::to_string(int(error)) + ")");
}

} // namespace

RayScene::RayScene(const Scene& scene) : embree_(std::make_unique<Embree>()) {
    embree_->device = rtcNewDevice(nullptr);
    if (!embree_->device) throw std::runtime_error("Embree: cannot create a device");
    rtcSetDeviceErrorFunction(embree_->device, reportEmbreeError, nullptr);
    embree_->scene = rtcNewScene(embree_->device);
    // Robust traversal: no ray slips through the shared edge of two triangles, which on a
    // closed box would leak light.
    rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);

    std::vector<std::unique_ptr<Geometry>> baked;
    Aabb bounds;
    for (const Instance& instance : scene.instances) {
        auto g = bake(scene, instance);
        if (g->indices.empty()) continue;
        for (const glm::vec3& p : g->positions)
            bounds.extend(p);
        baked.push_back(std::move(g));
    }
    // The offset must dwarf the rounding of a world position (about 1e-7 of its magnitude) yet
    // stay far below any feature of the scene.
    const float magnitude = bounds.empty()
                                ? 1.0f
                                : glm::length(bounds.size()) +
                                      std::max(glm::length(bounds.min), glm::length(bounds.max));
    // Relative to the scene alone: a floor in absolute units would be most of a tiny scene.
    epsilon_ = 2e-5f * std::max(magnitude, std::numeric_limits<float>::min());
    // Embree sees the scene scaled by a power of two to a magnitude near 1. Its robust
    // intersector drops the barycentrics of a hit whose determinant (the triangle's doubled area
    // seen along the ray) is below 1e-18 in squared units: at 1e-9 units every hit was reported
    // at a vertex. Scaling by a power of two is exact, so a scene near unit size gets the same
    // hits, bit for bit, as without it.
    toEmbree_ = std::exp2(-std::round(std::log2(std::max(magnitude, 1e-30f))));

    for (auto& g : baked) {
        RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<glm::vec3*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                    sizeof(glm::vec3), g->positions.size()));
        for (size_t i = 0; i < g->positions.size(); ++i)
            vertices[i] = g->positions[i] * toEmbree_;
        auto* indices = static_cast<uint32_t*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(uint32_t), g->indices.size() / 3));
        std::memcpy(indices, g->indices.data(), g->indices.size() * sizeof(uint32_t));
        checkDevice(embree_->device, "creating a triangle mesh");
        if (g->material->alphaMask) {
            rtcSetGeometryUserData(geometry, g.get());
            rtcSetGeometryIntersectFilterFunction(geometry, alphaMaskFilter);
            rtcSetGeometryOccludedFilterFunction(geometry, alphaMaskFilter);
        }
        rtcCommitGeometry(geometry);
        const unsigned id = rtcAttachGeometry(embree_->scene, geometry);
        rtcReleaseGeometry(geometry);
        if (id >= geometries_.size()) geometries_.resize(id + 1);
        geometries_[id] = std::move(g);
    }
    rtcCommitScene(embree_->scene);
    checkDevice(embree_->device, "building the scene");
}

RayScene::~RayScene() = default;

bool RayScene::intersect(glm::vec3 origin, glm::vec3 direction, float tfar, Surface& hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    const glm::vec3 o = origin * toEmbree_;
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
    rh.ray.dir_x = direction.x, rh.ray.dir_y = direction.y, rh.ray.dir_z = direction.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = tfar * toEmbree_;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_->scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

    const Geometry& g = *geometries_[rh.hit.geomID];
    const uint32_t* tri = &g.indices[3 * size_t(rh.hit.primID)];
    const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
    // Barycentric interpolation places the point on the triangle itself, not wherever the
    // rounding of origin + t * direction leaves it.
    hit.position = w * g.positions[tri[0]] + u * g.positions[tri[1]] + v * g.positions[tri[2]];
    glm::vec3 ng = glm::cross(g.positions[tri[1]] - g.positions[tri[0]],
                              g.positions[tri[2]] - g.positions[tri[0]]);
    const float ngLength = glm::length(ng);
    ng = ngLength > 0.0f ? ng / ngLength : -direction;
    glm::vec3 n = w * g.normals[tri[0]] + u * g.normals[tri[1]] + v * g.normals[tri[2]];
    const float nLength = glm::length(n);
    n = nLength > 1e-12f && std::isfinite(nLength) ? n / nLength : ng;
    // Two-sided: each normal is turned toward the viewer separately, as the G-buffer does
    // with the interpolated normal.
    hit.geometricNormal = glm::dot(ng, direction) > 0.0f ? -ng : ng;
    hit.normal = glm::dot(n, direction) > 0.0f ? -n : n;
    hit.albedo = glm::vec3(baseColor(*g.material, g.texture, interpolatedUv(g, rh.hit.primID, u, v),
                                     interpolatedColor(g, rh.hit.primID, u, v)));
    return true;
}

bool RayScene::occluded(glm::vec3 origin, glm::vec3 direction, float tfar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    const glm::vec3 o = origin * toEmbree_;
    ray.org_x = o.x, ray.org_y = o.y, ray.org_z = o.z;
    ray.dir_x = direction.x, ray.dir_y = direction.y, ray.dir_z = direction.z;
    ray.tnear = 0.0f;
    ray.tfar = tfar * toEmbree_;
    ray.mask = 0xffffffffu;
    rtcOccluded1(embree_->scene, &context, &ray);
    return ray.tfar < 0.0f; // Embree marks an occluded ray with tfar = -inf
}

glm::vec3 RayScene::rayOrigin(const Surface& surface, glm::vec3 direction) const {
    const float side = glm::dot(direction, surface.geometricNormal) >= 0.0f ? 1.0f : -1.0f;
    return surface.position + side * epsilon_ * surface.geometricNormal;
}

} // namespace ssgi::reference
