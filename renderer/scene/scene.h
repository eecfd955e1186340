// The scene model: no more than a scene needs. Diffuse surfaces, one spot light, a sky, a
// camera and a camera path, plus the settings the methods read. Loaders fill it; the renderer
// and the reference path tracer read it.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_precision.hpp>

#include "scene/settings.h"

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace ssgi {

// Any problem with input (file missing, malformed, unknown key, absurd value). The message
// names the file and the problem; programs print it and exit non-zero.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Vertex {
    glm::vec3 position; // object space
    glm::vec3 normal;   // object space, unit length
    glm::vec2 uv;
    // Linear RGBA that multiplies the material's base colour (glTF COLOR_0), as 16-bit unsigned
    // normalized numbers: the GPU and the path tracer read the same values. Used only where the
    // mesh says it has vertex colours.
    glm::u16vec4 color{65535};
};
static_assert(sizeof(Vertex) == 40);

// How a texture is read between and beyond its texels (a glTF sampler). There are no mip maps:
// a minification filter's mipmap part has no image to read.
enum class TextureWrap : uint8_t { Repeat, ClampToEdge, MirroredRepeat };
struct TextureSampler {
    TextureWrap wrapU = TextureWrap::Repeat, wrapV = TextureWrap::Repeat;
    bool magnifyNearest = false, minifyNearest = false; // false: bilinear
    bool operator==(const TextureSampler&) const = default;
    auto operator<=>(const TextureSampler&) const = default;
};

// Lambertian: albedo = baseColorFactor * baseColorTexture (texture is sRGB-encoded) * the
// vertex colour where the mesh has one. Every surface is two-sided: both renderers shade each
// side with the normal turned toward the side it is seen from.
struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    int baseColorTexture = -1; // index into Scene::textures, -1 = none
    TextureSampler baseColorSampler;
    bool alphaMask = false; // glTF alphaMode MASK
    float alphaCutoff = 0.5f;
};

// 8-bit RGBA, sRGB-encoded, rows top to bottom.
struct Texture {
    std::string name;
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

// One triangle list with one material (a glTF primitive or a procedural primitive).
struct Mesh {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    int material = 0;
    bool vertexColors = false; // whether Vertex::color multiplies the albedo
};

// A mesh placed in the world (glTF node transform, or identity for primitives). `name` is the
// scene file object's or the glTF node's, which object paths refer to.
struct Instance {
    int mesh = 0;
    glm::mat4 transform{1.0f};
    std::string name;
};

// A moving object (the thesis assumes a static scene): keys of a translation added to the
// placement of every instance named `object`, interpolated linearly and held beyond the ends.
struct ObjectKey {
    float time = 0.0f;
    glm::vec3 translation{0.0f};
};
struct ObjectPath {
    std::string object;
    std::vector<ObjectKey> keys; // sorted by time
    std::vector<int> instances;  // the instances it moves
};

struct Aabb {
    glm::vec3 min{1e30f};
    glm::vec3 max{-1e30f};
    void extend(glm::vec3 p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    bool empty() const { return min.x > max.x; }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 size() const { return max - min; }
};

// The one light: a spot light whose emitting disk has `radius` (0 = point light). Radiant
// intensity along the axis is `intensity * color` (W/sr); it falls smoothly to 0 between the
// inner and outer cone half-angles (glTF KHR_lights_punctual spot rule).
struct SpotLight {
    glm::vec3 position{0.0f, 1.0f, 0.0f};
    glm::vec3 direction{0.0f, -1.0f, 0.0f}; // unit
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float innerConeAngle = 0.0f;       // radians, half-angle
    float outerConeAngle = 0.7853982f; // radians, half-angle, < 90 degrees
    float radius = 0.0f;               // disk radius (soft shadows); 0 = point
    bool operator==(const SpotLight&) const = default;
};

// Radiance of the sky seen from the scene: a vertical gradient from horizon to zenith (equal
// colours give a constant sky). Below the horizon the sky is `ground`.
struct Sky {
    glm::vec3 zenith{0.0f};
    glm::vec3 horizon{0.0f};
    glm::vec3 ground{0.0f};
};

// Pinhole camera: orientation rotates the camera's -Z (view direction) and +Y (up) into world.
struct Camera {
    glm::vec3 position{0.0f, 0.0f, 3.0f};
    glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
    float yfov = 0.6981317f; // radians, vertical field of view
    float znear = 0.01f;     // derived from the scene bounds when the file does not say
    float zfar = 100.0f;
};

struct CameraKey {
    float time = 0.0f; // seconds
    Camera camera;
    // A camera cut: the path jumps here, and the frame that reaches this key starts every cached
    // history afresh (as a reset on a cut does in temporal upscalers and denoisers).
    bool cut = false;
};

// Keyframes sorted by time; interpolated (position linear, orientation slerp, fov linear).
struct CameraPath {
    std::vector<CameraKey> keys;
    bool empty() const { return keys.empty(); }
};

struct Scene {
    std::string sourcePath; // the file it was loaded from
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Instance> instances;
    SpotLight light;
    Sky sky;
    Camera camera;
    CameraPath cameraPath;
    std::vector<ObjectPath> objectPaths;
    Aabb bounds; // world space, over all instances, wherever their paths take them
    // The diagonal the derived AO radius is a share of (aoRadius): the bounds' own, but a bare
    // model's without the ground plane staged under it (0: the bounds').
    float aoDiagonal = 0.0f;
    Settings settings; // the method settings (settings.h), defaults where nothing set them
};

// Loads a scene description file (.json) or a bare glTF (.gltf/.glb, staged with a camera,
// light, daylight sky and ground plane derived from its bounds: bare_model.h). `overrides`
// (e.g. `render --set`) override the file's settings and are seen while loading, as
// ground_plane must be. Throws InputError naming the file and the problem.
Scene loadScene(const std::string& path, const SettingOverrides& overrides = {});

// The ambient-occlusion radius in scene units: the ao_radius setting when > 0, else 1.25% of the
// scene's bounding-box diagonal where the sky's visibility takes the occluders beyond it
// (hasSkyVisibility), 5% where the AO stands for all of the sky's occlusion. The real-time AO
// and the reference's AO use the same value.
float aoRadius(const Scene& scene);
// Whether the frame looks up the sky's visibility (addSkyVisibilityPasses): on, beside the AO
// (SSDO occludes the sky by itself), under a sky that is not black (none to see there).
bool hasSkyVisibility(const Scene& scene);
// Whether the world cache's cells hold the sky's visibility beside the bounce, in place of the
// per-pixel pass: where there is one, with the world cache's bounce (indirect_method 3) and
// world_sky_visibility.
bool skyInWorldCache(const Scene& scene);

} // namespace ssgi
