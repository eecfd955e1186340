#include "scene/bare_model.h"

#include "scene/primitives.h"

#include <algorithm>
#include <cmath>

namespace ssgi {

namespace {

constexpr glm::vec3 kUp(0.0f, 1.0f, 0.0f);

float boundingRadius(const Aabb& model) {
    return 0.5f * glm::length(model.size());
}

// The unit vector `degreesUp` above the horizontal unit vector `across`.
glm::vec3 raised(glm::vec3 across, float degreesUp) {
    const float up = glm::radians(degreesUp);
    return std::cos(up) * across + std::sin(up) * kUp;
}

// `across` turned about the vertical by `degrees` (counter-clockwise seen from above).
glm::vec3 turned(glm::vec3 across, float degrees) {
    const float a = glm::radians(degrees);
    return {across.x * std::cos(a) + across.z * std::sin(a), 0.0f,
            -across.x * std::sin(a) + across.z * std::cos(a)};
}

} // namespace

Camera bareModelCamera(const Aabb& model) {
    Camera camera;
    camera.yfov = glm::radians(45.0f);
    const glm::vec3 center = model.center();
    const glm::vec3 back = raised(turned(glm::vec3(0, 0, 1), 35.0f), 30.0f); // centre -> camera
    const glm::vec3 right = glm::normalize(glm::cross(-back, kUp));
    const glm::vec3 up = glm::cross(right, -back);
    // A corner at q (from the centre) is seen at depth d - q·back from a camera at distance d;
    // it is inside the frame when its offsets across the view are within `slope` of that depth.
    const float slope = 0.9f * std::tan(0.5f * camera.yfov);
    float distance = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 q = glm::vec3(corner & 1 ? model.max.x : model.min.x,
                                      corner & 2 ? model.max.y : model.min.y,
                                      corner & 4 ? model.max.z : model.min.z) -
                            center;
        const float across = std::max(std::abs(glm::dot(q, right)), std::abs(glm::dot(q, up)));
        distance = std::max(distance, glm::dot(q, back) + across / slope);
    }
    camera.position = center + distance * back;
    camera.orientation = glm::quatLookAtRH(-back, kUp);
    camera.znear = camera.zfar = 0.0f;
    return camera;
}

SpotLight bareModelLight(const Aabb& model, const Camera& camera) {
    const glm::vec3 center = model.center();
    const float radius = boundingRadius(model);
    // The camera's side of the model, seen from above; a camera straight above or below the
    // centre has none, and then its view direction (or, failing that, +Z) decides. Each floor
    // is relative to its vector's scale: the model's radius for the camera's offset (a model
    // 1e-9 units wide lies 1e-9 units from its camera), 1 for the unit view direction.
    glm::vec3 side = camera.position - center;
    side.y = 0.0f;
    float scale = radius;
    if (glm::length(side) <= 1e-6f * radius) {
        side = camera.orientation * glm::vec3(0, 0, 1);
        side.y = 0.0f;
        scale = 1.0f;
    }
    side = glm::length(side) > 1e-6f * scale ? glm::normalize(side) : glm::vec3(0, 0, 1);
    const glm::vec3 toLight = raised(turned(side, 40.0f), 55.0f);
    constexpr float kDistance = 4.0f; // bounding radii
    SpotLight light;
    light.position = center + kDistance * radius * toLight;
    light.direction = -toLight;
    // Full intensity over the bounding sphere, fading out a little beyond it on the ground.
    light.innerConeAngle = std::asin(1.0f / kDistance);
    light.outerConeAngle = 1.3f * light.innerConeAngle;
    const float distance = kDistance * radius;
    light.intensity = kBareModelIrradiance * distance * distance;
    light.color = glm::vec3(1.0f, 0.96f, 0.9f); // a little warmer than the sky
    light.radius = 0.05f * radius;
    return light;
}

Sky daylightSky() {
    Sky sky;
    sky.zenith = glm::vec3(0.22f, 0.27f, 0.35f);
    sky.horizon = glm::vec3(0.34f, 0.36f, 0.4f);
    // What the ground plane shows far from the light: its albedo times the sky light on an
    // upward surface (the zenith's colour in the composite's estimate).
    sky.ground = kGroundAlbedo * sky.zenith;
    return sky;
}

bool hasGround(const Scene& scene, const Aabb& model) {
    const float lowest = model.min.y + 0.01f * model.size().y;
    double covered = 0.0;
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[size_t(instance.mesh)];
        // Front faces run counter-clockwise (glTF), unless the transform mirrors them.
        const float facing = glm::determinant(glm::mat3(instance.transform)) < 0.0f ? -1.0f : 1.0f;
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            glm::vec3 p[3];
            bool low = true;
            for (int k = 0; k < 3; ++k) {
                const Vertex& v = mesh.vertices[mesh.indices[t + size_t(k)]];
                p[k] = glm::vec3(instance.transform * glm::vec4(v.position, 1.0f));
                low = low && p[k].y <= lowest;
            }
            const float up = facing * glm::cross(p[1] - p[0], p[2] - p[0]).y;
            if (low && up > 0.0f) covered += 0.5 * double(up);
        }
    }
    const double footprint = double(model.size().x) * double(model.size().z);
    return covered > 0.0 && covered >= 0.5 * footprint;
}

void addGroundPlane(Scene& scene, const Aabb& model) {
    const float reach = 25.0f * boundingRadius(model);
    // At the lowest point, not below it: a closed model stands on the plane. Any gap is a slot
    // under its base that a pixel-centre ray along its lower edge can look into, where the path
    // tracer (rightly) finds no light and the real-time image does. A flat base lies in the
    // plane, facing down; no camera or light above the plane sees it, so nothing fights for depth.
    const float y = model.min.y;
    const glm::vec3 c = model.center();
    Material ground;
    ground.name = "ground";
    ground.baseColorFactor = glm::vec4(glm::vec3(kGroundAlbedo), 1.0f);
    scene.materials.push_back(ground);
    // Counter-clockwise seen from above: the normal faces up.
    const std::array<glm::vec3, 4> corners = {
        glm::vec3(c.x + reach, y, c.z - reach), glm::vec3(c.x - reach, y, c.z - reach),
        glm::vec3(c.x - reach, y, c.z + reach), glm::vec3(c.x + reach, y, c.z + reach)};
    scene.meshes.push_back(makeQuad(corners, int(scene.materials.size()) - 1));
    scene.instances.push_back({int(scene.meshes.size()) - 1, glm::mat4(1.0f), "ground"});
}

} // namespace ssgi
