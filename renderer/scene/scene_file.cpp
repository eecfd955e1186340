// loadScene(): a scene description file, or a bare glTF, into the scene model. What the files
// leave out (light, camera, clip planes) is derived from the scene's bounds; a bare glTF is also
// staged (bare_model.h): its own camera and light, a daylight sky and a ground plane.
#include "scene/animation.h"
#include "scene/bare_model.h"
#include "scene/gltf_internal.h"
#include "scene/primitives.h"
#include "scene/scene_json.h"
#include "scene/warnings.h"

#include <glm/gtx/component_wise.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace ssgi {

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& problem) {
    throw InputError(file + ": " + problem);
}

// Scene files keep coordinates within 1e9 and their objects within about 2e9; beyond 1e10
// (reachable only through a glTF's absurd positions, transforms or gltf_scale) the derived
// light and camera, which square distances, and depth precision break down.
constexpr float kFarthest = 1e10f;
// False also for NaN (from inf - inf), which Aabb::extend would silently skip.
bool withinReach(glm::vec3 p) {
    return glm::all(glm::lessThanEqual(glm::abs(p), glm::vec3(kFarthest)));
}

Aabb worldBounds(const Scene& scene, const std::string& file) {
    Aabb bounds;
    for (const Instance& instance : scene.instances) {
        for (const Vertex& vertex : scene.meshes[size_t(instance.mesh)].vertices) {
            const glm::vec3 p = glm::vec3(instance.transform * glm::vec4(vertex.position, 1.0f));
            if (!withinReach(p))
                fail(file, "a vertex lies beyond 1e10 units from the origin (coordinates, node "
                           "transforms or gltf_scale too large)");
            bounds.extend(p);
        }
    }
    return bounds;
}

// The scene model keeps 32-bit floats, which step by 6e-8 of a coordinate's size: a scene 1e5
// units from the origin has its corners, camera and light rounded to 4 mm as they are read. The
// renderer moves everything next to the origin before the GPU sees it (renderer.cpp:
// gpuOrigin), so what remains is that rounding; past 1e-4 of the scene's size it is said, with
// the limit measured with the Cornell box (0.96 units) moved along every axis and rendered at
// 32x32, 64x64 and 128x128 against its image at the origin, at 8 offsets across one step of the
// float grid each (docs/robustness.md): within relMSE 0.02 while the step is at most 0.025% of
// its size, up to 4096 units from the origin (at most 0.011), and not beyond (0.05%: up to 0.13;
// 1e5 units, 0.8%: 0.08 to 1.3, some offsets black). Edges and shadow boundaries that the
// rounding moves across a pixel's centre make most of the figure.
void warnIfFarFromTheOrigin(const Aabb& bounds, const std::string& file) {
    const float farthest = glm::compMax(glm::max(glm::abs(bounds.min), glm::abs(bounds.max)));
    const float size = glm::length(bounds.size());
    const float step = std::nextafter(farthest, INFINITY) - farthest;
    if (step <= 1e-4f * size) return;
    char text[400];
    std::snprintf(text, sizeof text,
                  "the scene lies %.3g units from the origin, where 32-bit floats step by %.3g "
                  "units (%.2g%% of its %.3g-unit size)",
                  double(farthest), double(step), 100.0 * step / size, double(size));
    warn(file + ": " + text +
         ": its coordinates, camera and light are rounded by up to half that, which "
         "moves edges and shadows and can close gaps narrower than the step (the "
         "Cornell box stays within relMSE 0.02 of its image at the origin while the step "
         "is at most 0.025% of its size, 4096 units away, and not beyond); move it "
         "nearer the origin for an exact image");
}

// A scene file's light when it names none: straight down from just below the top of the bounds (so
// a closed room's ceiling does not hide it), bright enough for an irradiance of about 1 on the
// floor beneath it.
SpotLight defaultLight(const Aabb& bounds) {
    const glm::vec3 size = bounds.size();
    SpotLight light;
    light.position = bounds.center() +
                     glm::vec3(0.0f, std::max(0.45f * size.y, 0.05f * glm::length(size)), 0.0f);
    light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    light.outerConeAngle = glm::radians(60.0f);
    light.innerConeAngle = 0.0f;
    const float toFloor = light.position.y - bounds.min.y;
    light.intensity = toFloor * toFloor;
    return light;
}

// A scene file's camera when it names none: from +Z towards the centre, far enough that the
// bounding sphere fits a 45 degree view. Clip planes are left at 0 for fillClipPlanes().
Camera defaultCamera(const Aabb& bounds) {
    Camera camera;
    camera.yfov = glm::radians(45.0f);
    const float radius = 0.5f * glm::length(bounds.size());
    camera.position =
        bounds.center() + glm::vec3(0.0f, 0.0f, radius / std::sin(0.5f * camera.yfov));
    camera.orientation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f); // identity already looks down -Z
    camera.znear = camera.zfar = 0.0f;
    return camera;
}

// Clip planes not given (0) are fitted to the bounds seen from the camera: far beyond the
// farthest corner, near as far out as depth precision needs.
void fillClipPlanes(Camera& camera, const Aabb& bounds) {
    float farthest = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p(corner & 1 ? bounds.max.x : bounds.min.x,
                          corner & 2 ? bounds.max.y : bounds.min.y,
                          corner & 4 ? bounds.max.z : bounds.min.z);
        farthest = std::max(farthest, glm::distance(camera.position, p));
    }
    if (camera.zfar <= 0.0f) camera.zfar = std::max(2.0f * farthest, 2.0f * camera.znear);
    if (camera.znear <= 0.0f)
        camera.znear = std::max(camera.zfar / 1e4f, 1e-4f * glm::length(bounds.size()));
    if (camera.znear >= camera.zfar) camera.znear = camera.zfar * 1e-4f;
}

// Clip planes the renderer and the path tracer can draw with; a near plane beyond every point
// of the scene draws nothing.
void checkClipPlanes(const Camera& camera, const Aabb& bounds, const std::string& file,
                     const std::string& where) {
    auto text = [](float x) {
        std::ostringstream out;
        out << x;
        return out.str();
    };
    if (camera.zfar > kMaxClipRatio * camera.znear)
        fail(file, "'" + where + "': near " + text(camera.znear) + " is less than far (" +
                       text(camera.zfar) + ") / " + text(kMaxClipRatio) +
                       ", beyond the depth precision of the renderer and the path tracer");
    float farthest = 0.0f;
    for (int corner = 0; corner < 8; ++corner)
        farthest =
            std::max(farthest, glm::distance(camera.position,
                                             glm::vec3(corner & 1 ? bounds.max.x : bounds.min.x,
                                                       corner & 2 ? bounds.max.y : bounds.min.y,
                                                       corner & 4 ? bounds.max.z : bounds.min.z)));
    if (camera.znear >= farthest)
        fail(file, "'" + where + "': near " + text(camera.znear) +
                       " is beyond the farthest point of the scene (" + text(farthest) +
                       " from the camera): nothing would be drawn");
}

Camera applyCameraSpec(const CameraSpec& spec, Camera camera, const std::string& file) {
    if (spec.position) camera.position = *spec.position;
    std::optional<glm::vec3> forward;
    if (spec.target) {
        forward = *spec.target - camera.position;
        if (glm::length(*forward) == 0.0f)
            fail(file, "'" + spec.where + ".target' equals the camera position");
    } else if (spec.direction) {
        forward = *spec.direction;
    }
    if (forward || spec.up) {
        const glm::vec3 view =
            glm::normalize(forward.value_or(camera.orientation * glm::vec3(0.0f, 0.0f, -1.0f)));
        const glm::vec3 up = glm::normalize(spec.up.value_or(glm::vec3(0.0f, 1.0f, 0.0f)));
        if (std::abs(glm::dot(view, up)) > 0.999999f)
            fail(file, "'" + spec.where + "': the view direction is parallel to 'up'");
        camera.orientation = glm::quatLookAtRH(view, up);
    }
    if (spec.yfovDegrees) camera.yfov = glm::radians(*spec.yfovDegrees);
    if (spec.znear) camera.znear = *spec.znear;
    if (spec.zfar) camera.zfar = *spec.zfar;
    return camera;
}

SpotLight applyLightSpec(const LightSpec& spec, SpotLight light, const std::string& file) {
    if (spec.position) light.position = *spec.position;
    if (spec.target) {
        const glm::vec3 toTarget = *spec.target - light.position;
        if (glm::length(toTarget) == 0.0f) fail(file, "'light.target' equals the light position");
        light.direction = glm::normalize(toTarget);
    } else if (spec.direction) {
        light.direction = glm::normalize(*spec.direction);
    }
    if (spec.color) light.color = *spec.color;
    if (spec.intensity) light.intensity = *spec.intensity;
    if (spec.radius) light.radius = *spec.radius;
    if (spec.coneDegrees) {
        light.outerConeAngle = glm::radians(*spec.coneDegrees);
        light.innerConeAngle = glm::radians(spec.innerConeDegrees.value_or(0.0f));
    } else if (spec.innerConeDegrees) {
        light.innerConeAngle = glm::radians(*spec.innerConeDegrees);
        if (light.innerConeAngle >= light.outerConeAngle)
            fail(file, "'light.inner_cone_deg' must be less than the light's cone angle (" +
                           std::to_string(glm::degrees(light.outerConeAngle)) + " degrees)");
    }
    return light;
}

void addObjects(const SceneDescription& description, const std::string& file, Scene& scene) {
    const int firstMaterial = int(scene.materials.size());
    scene.materials.insert(scene.materials.end(), description.materials.begin(),
                           description.materials.end());
    for (const ObjectSpec& object : description.objects) {
        const auto named = std::find_if(
            description.materials.begin(), description.materials.end(),
            [&](const Material& material) { return material.name == object.material; });
        const int material = firstMaterial + int(named - description.materials.begin());
        Mesh mesh;
        switch (object.type) {
        case ObjectSpec::Type::Quad:
            if (glm::length(quadNormal(object.corners)) == 0.0f)
                fail(file, "'" + object.where + ".corners' enclose no area");
            mesh = makeQuad(object.corners, material);
            break;
        case ObjectSpec::Type::Box:
            mesh = makeBox(object.center, object.size, object.rotateYDegrees, material);
            break;
        case ObjectSpec::Type::Sphere:
            mesh = makeSphere(object.center, object.radius, object.segments, material);
            break;
        }
        scene.meshes.push_back(std::move(mesh));
        scene.instances.push_back({int(scene.meshes.size()) - 1, glm::mat4(1.0f), object.name});
    }
}

// The ground plane is asked for by the ground_plane setting (the command line's, else the scene
// file's); by default (-1) a bare glTF gets one and a scene file does not, so scene files written
// before the setting render as they did.
bool wantsGround(const Settings& settings, bool bare) {
    return settings.ground_plane < 0 ? bare : settings.ground_plane == 1;
}

Scene buildScene(const std::string& path, const SceneDescription& description, bool bare,
                 const SettingOverrides& overrides) {
    Scene scene;
    scene.sourcePath = path;
    scene.settings = withOverrides(withOverrides({}, description.settings, path), overrides, path);
    GltfViewpoint viewpoint;
    for (const std::string& gltfPath : description.gltfPaths) {
        GltfViewpoint found;
        try {
            found = loadGltf(gltfPath, description.gltfScale, scene);
        } catch (const InputError& error) {
            if (gltfPath == path) throw;
            fail(path, error.what()); // name the scene file as well as the glTF it refers to
        }
        if (!viewpoint.camera) viewpoint.camera = found.camera;
        if (!viewpoint.light) viewpoint.light = found.light;
    }
    // Clip planes and the light's frustum are derived from distances to the bounds.
    if (viewpoint.camera && !withinReach(viewpoint.camera->position))
        fail(path, "the glTF camera lies beyond 1e10 units from the origin");
    if (viewpoint.light && !withinReach(viewpoint.light->position))
        fail(path, "the glTF light lies beyond 1e10 units from the origin");
    addObjects(description, path, scene);
    scene.bounds = worldBounds(scene, path);
    scene.objectPaths = description.objectPaths;
    resolveObjectPaths(scene, path);
    if (scene.bounds.empty()) fail(path, "the scene has no triangles");
    if (glm::length(scene.bounds.size()) == 0.0f) fail(path, "all of the scene is at one point");
    warnIfFarFromTheOrigin(scene.bounds, path);

    // The camera, light and ground plane fit the model (what the files hold), not the plane.
    const Aabb model = scene.bounds;
    if (wantsGround(scene.settings, bare) && !hasGround(scene, model)) {
        addGroundPlane(scene, model);
        for (const Vertex& vertex : scene.meshes.back().vertices)
            scene.bounds.extend(vertex.position);
        // The AO radius stays the model's, not a share of the far larger ground's diagonal.
        scene.aoDiagonal = glm::length(model.size());
    }

    // Path keys refine the scene camera as written, before its clip planes are derived, so a
    // key that moves the camera gets clip planes fitted to where it is.
    Camera camera = viewpoint.camera.value_or(bare ? bareModelCamera(model) : defaultCamera(model));
    if (description.camera) camera = applyCameraSpec(*description.camera, camera, path);
    for (const auto& [time, spec] : description.cameraPath) {
        CameraKey key{time, applyCameraSpec(spec, camera, path), spec.cut};
        fillClipPlanes(key.camera, scene.bounds);
        checkClipPlanes(key.camera, scene.bounds, path, spec.where);
        scene.cameraPath.keys.push_back(key);
    }

    scene.light =
        viewpoint.light.value_or(bare ? bareModelLight(model, camera) : defaultLight(model));
    if (description.light) scene.light = applyLightSpec(*description.light, scene.light, path);
    scene.sky = description.sky;

    fillClipPlanes(camera, scene.bounds);
    checkClipPlanes(camera, scene.bounds, path, "camera");
    scene.camera = camera;
    return scene;
}

} // namespace

Scene loadScene(const std::string& path, const SettingOverrides& overrides) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    SceneDescription description;
    const bool bare = extension == ".gltf" || extension == ".glb";
    if (bare) {
        description.gltfPaths = {path};
        description.sky = daylightSky();
    } else if (extension == ".json") {
        description = readSceneDescription(path);
    } else {
        fail(path, "unsupported file type '" + extension + "' (expected .json, .gltf or .glb)");
    }
    return buildScene(path, description, bare, overrides);
}

} // namespace ssgi
