// libFuzzer target over the scene loader: every input is loaded as a glTF (binary when it starts
// with "glTF", else as JSON text both as a .gltf and as a scene file .json). The loader promises
// that anything it throws is an InputError and that whatever it returns is a scene the renderer
// can draw (indices, materials and textures in range, every number finite). A crash, a hang, an
// out-of-memory, a sanitizer report or a broken promise is a finding; an InputError is the loader
// doing its job.
#include "scene/scene.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <streambuf>
#include <string>
#include <sys/stat.h>
#include <typeinfo>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

// Scene files name their glTF relative to themselves ("models/bunny.glb" from scenes/,
// "../models/bunny.glb" from scenes/stability/). Inputs are written under a private root whose
// models/ folders hold every such name as a link to the smallest real model, so mutated
// scene files reach buildScene() without loading a large model on every run.
fs::path gRoot, gInputDir;
// SSGI_FUZZ_VERBOSE=1 prints the loader's messages, to see why a replayed input is rejected.
bool gVerbose = false;

// Warnings of the loader are expected by the thousand; they would drown libFuzzer's own output
// (which goes through stdio, not std::cerr).
struct NullBuffer : std::streambuf {
    int overflow(int c) override { return c; }
} gNull;

void removeRoot() {
    std::error_code ignored;
    fs::remove_all(gRoot, ignored);
}

// A finding: libFuzzer saves the input when the process aborts. (After a sanitizer report or a
// crash the private folder stays behind in the temporary folder.)
[[noreturn]] void finding(const std::string& message) {
    std::fprintf(stderr, "%s\n", message.c_str());
    removeRoot();
    std::abort();
}

void check(bool condition, const char* what) {
    if (!condition) finding(std::string("loader broke its promise: ") + what);
}

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// What the renderer and the reference assume of a loaded scene.
void checkScene(const ssgi::Scene& scene) {
    check(!scene.bounds.empty() && finite(scene.bounds.min) && finite(scene.bounds.max),
          "bounds empty or not finite");
    for (const ssgi::Texture& texture : scene.textures)
        check(texture.width > 0 && texture.height > 0 &&
                  texture.rgba.size() == size_t(texture.width) * texture.height * 4,
              "texture size");
    for (const ssgi::Material& material : scene.materials) {
        check(material.baseColorTexture < int(scene.textures.size()) &&
                  material.baseColorTexture >= -1,
              "material texture index");
        for (int c = 0; c < 4; ++c)
            check(std::isfinite(material.baseColorFactor[c]) && material.baseColorFactor[c] >= 0.0f,
                  "material base colour not finite or negative");
    }
    for (const ssgi::Mesh& mesh : scene.meshes) {
        check(mesh.material >= 0 && size_t(mesh.material) < scene.materials.size(),
              "mesh material index");
        check(mesh.indices.size() % 3 == 0, "index count not a multiple of 3");
        for (uint32_t index : mesh.indices)
            check(index < mesh.vertices.size(), "index out of range");
        for (const ssgi::Vertex& vertex : mesh.vertices) {
            check(finite(vertex.position), "vertex position not finite");
            check(finite(vertex.normal) && std::abs(glm::length(vertex.normal) - 1.0f) < 1e-3f,
                  "vertex normal not unit length");
            check(std::isfinite(vertex.uv.x) && std::isfinite(vertex.uv.y), "uv not finite");
        }
    }
    for (const ssgi::Instance& instance : scene.instances) {
        check(instance.mesh >= 0 && size_t(instance.mesh) < scene.meshes.size(),
              "instance mesh index");
        for (int c = 0; c < 4; ++c)
            check(finite(glm::vec3(instance.transform[c])) &&
                      std::isfinite(instance.transform[c][3]),
                  "instance transform not finite");
    }
    auto checkCamera = [](const ssgi::Camera& camera) {
        check(finite(camera.position), "camera position not finite");
        check(std::isfinite(camera.orientation.w) && std::isfinite(camera.orientation.x) &&
                  std::isfinite(camera.orientation.y) && std::isfinite(camera.orientation.z),
              "camera orientation not finite");
        check(camera.yfov > 0.0f && camera.yfov < 3.1416f, "camera yfov");
        check(camera.znear > 0.0f && camera.znear < camera.zfar && std::isfinite(camera.zfar),
              "camera clip planes");
    };
    checkCamera(scene.camera);
    for (const ssgi::CameraKey& key : scene.cameraPath.keys)
        checkCamera(key.camera);
    const ssgi::SpotLight& light = scene.light;
    check(finite(light.position) && finite(light.color) && std::isfinite(light.intensity) &&
              std::isfinite(light.radius) && light.intensity >= 0.0f &&
              glm::all(glm::greaterThanEqual(light.color, glm::vec3(0.0f))),
          "light not finite or negative");
    check(std::abs(glm::length(light.direction) - 1.0f) < 1e-3f, "light direction not unit");
    check(light.outerConeAngle > 0.0f && light.outerConeAngle < 1.5708f &&
              light.innerConeAngle >= 0.0f && light.innerConeAngle < light.outerConeAngle,
          "light cone angles");
}

void loadAs(const uint8_t* data, size_t size, const char* name) {
    const fs::path path = gInputDir / name;
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    try {
        checkScene(ssgi::loadScene(path.string()));
    } catch (const ssgi::InputError& error) {
        // Rejected with a message: what bad input should get. Shown when replaying a file.
        if (gVerbose) std::fprintf(stderr, "%s: InputError: %s\n", name, error.what());
    } catch (const std::exception& error) {
        // Programs report these as device errors (exit 1), not as bad input (exit 2).
        finding(std::string("loader threw ") + typeid(error).name() +
                " instead of InputError: " + error.what());
    }
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gVerbose = std::getenv("SSGI_FUZZ_VERBOSE") != nullptr;
    if (!gVerbose) std::cerr.rdbuf(&gNull);
    gRoot = fs::temp_directory_path() / ("ssgi-fuzz-" + std::to_string(getpid()));
    gInputDir = gRoot / "a" / "b" / "c";
    fs::create_directories(gInputDir);
    const fs::path models = std::string(SSGI_SOURCE_DIR) + "/scenes/models";
    const fs::path small = models / "cornell-box.glb";
    for (const fs::path& scenes : {gInputDir / "models", gRoot / "a" / "b" / "models"}) {
        fs::create_directories(scenes);
        std::error_code ignored;
        if (fs::exists(models) && fs::exists(small))
            for (const auto& entry : fs::directory_iterator(models))
                if (entry.path().extension() == ".glb")
                    fs::create_symlink(small, scenes / entry.path().filename(), ignored);
    }
    // Files a mutated .gltf can name as a buffer or image (seeded by tests/fuzz/seeds/): one
    // triangle beside it and one a folder up, and what must be refused without being opened —
    // a folder, a FIFO (opening it would hang), a device (reading it would never end).
    {
        const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        const uint32_t corners[3] = {0, 1, 2};
        for (const fs::path& bin : {gInputDir / "mesh.bin", gInputDir.parent_path() / "up.bin"}) {
            std::ofstream out(bin, std::ios::binary);
            out.write(reinterpret_cast<const char*>(triangle), sizeof triangle);
            out.write(reinterpret_cast<const char*>(corners), sizeof corners);
        }
        std::error_code ignored;
        fs::create_directories(gInputDir / "folder.bin", ignored);
        mkfifo((gInputDir / "fifo.bin").c_str(), 0600);
        fs::create_symlink("/dev/zero", gInputDir / "zero.bin", ignored);
    }
    std::atexit(removeRoot);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size >= 4 && std::string_view(reinterpret_cast<const char*>(data), 4) == "glTF") {
        loadAs(data, size, "input.glb");
    } else {
        loadAs(data, size, "input.gltf");
        loadAs(data, size, "input.json");
    }
    return 0;
}
