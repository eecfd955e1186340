// Small glTF files written by the tests themselves (test_gltf_features, test_gltf_sparse): a
// builder for one-mesh .glb files, the floor quad they draw, and a fixture that writes a file
// with a scene file framing it and renders it with the real-time renderer and the path tracer.
// With SSGI_GLTF_FEATURES_DIR set the files are written there and kept (to render them with
// `render` and `reference`).
#pragma once

#include "metrics/metrics.h"
#include "reference/render.h"
#include "support.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <unistd.h>

namespace ssgi::test {

namespace fs = std::filesystem;
using nlohmann::json;

inline constexpr uint32_t kSize = 64;
inline constexpr int kFloat = 5126, kUnsignedByte = 5121, kUnsignedShort = 5123,
                     kUnsignedInt = 5125;

// A one-mesh glTF under construction: its JSON and the binary chunk of its .glb.
struct Gltf {
    json doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {{{"attributes", json::object()}, {"material", 0}}}}}}},
        {"materials", {{{"doubleSided", true}, {"pbrMetallicRoughness", {{"metallicFactor", 0}}}}}},
        {"bufferViews", json::array()},
        {"accessors", json::array()}};
    std::string bin;

    json& primitive() { return doc["meshes"][0]["primitives"][0]; }
    // The values as a new buffer view (4-byte aligned); its index.
    template <class T> int view(const std::vector<T>& values) {
        bin.resize((bin.size() + 3) / 4 * 4, '\0');
        const size_t offset = bin.size(), length = values.size() * sizeof(T);
        bin.resize(offset + length);
        std::memcpy(bin.data() + offset, values.data(), length);
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}});
        return int(doc["bufferViews"].size()) - 1;
    }
    // An accessor over buffer view `bufferView` (-1: none, every element zero); its index.
    int accessor(int bufferView, int componentType, size_t count, const char* type,
                 bool normalized = false) {
        json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
        if (bufferView >= 0) a["bufferView"] = bufferView;
        if (normalized) a["normalized"] = true;
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size()) - 1;
    }
    template <class T>
    int attribute(const char* name, const std::vector<T>& values, int componentType,
                  const char* type, int components, bool normalized = false) {
        const int a = accessor(view(values), componentType, values.size() / size_t(components),
                               type, normalized);
        primitive()["attributes"][name] = a;
        return a;
    }
    // The .glb: 12-byte header, JSON chunk (space padded), BIN chunk (zero padded).
    std::string glb() const {
        std::string data = bin;
        data.resize((data.size() + 3) / 4 * 4, '\0');
        json withBuffer = doc;
        withBuffer["buffers"] = {{{"byteLength", data.size()}}};
        std::string text = withBuffer.dump();
        text.resize((text.size() + 3) / 4 * 4, ' ');
        auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
        const uint32_t length = uint32_t(28 + text.size() + data.size());
        return "glTF" + u32(2) + u32(length) + u32(uint32_t(text.size())) + "JSON" + text +
               u32(uint32_t(data.size())) + "BIN" + std::string(1, '\0') + data;
    }
};

// The floor every test draws: a 2 x 2 quad at y = 0, normals up, uv from -1 to 2 on each axis.
// The loader refuses the file at `path` (case `name`) with an InputError whose message holds
// `message`.
inline void expectRefused(const std::string& path, const std::string& name,
                          const std::string& message) {
    try {
        loadScene(path);
        ADD_FAILURE() << name << " loaded";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find(message), std::string::npos)
            << name << ": " << error.what();
    }
}

inline const std::vector<float> kCorners = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
inline const std::vector<float> kUp = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
inline const std::vector<float> kUvs = {-1, -1, 2, -1, 2, 2, -1, 2};
inline const std::vector<uint32_t> kQuad = {0, 2, 1, 0, 3, 2};

inline Gltf floorGltf() {
    Gltf g;
    g.attribute("POSITION", kCorners, kFloat, "VEC3", 3);
    g.attribute("NORMAL", kUp, kFloat, "VEC3", 3);
    g.attribute("TEXCOORD_0", kUvs, kFloat, "VEC2", 2);
    g.primitive()["indices"] = g.accessor(g.view(kQuad), kUnsignedInt, kQuad.size(), "SCALAR");
    return g;
}

// The real-time frame and the path tracer's direct light of one scene, and their relMSE over
// the pixels with geometry.
struct Rendered {
    test::Frame frame;
    std::vector<float> reference;
    double relMse = 0.0;
    size_t geometryPixels = 0;
};

class GltfFiles : public test::VulkanTest {
protected:
    void SetUp() override {
        test::VulkanTest::SetUp();
        const char* keep = std::getenv("SSGI_GLTF_FEATURES_DIR");
        keep_ = keep && *keep;
        dir_ = keep_ ? fs::path(keep)
                     : fs::temp_directory_path() / ("ssgi-gltf-" + std::to_string(getpid()) + "-" +
                                                    std::to_string(std::random_device()()));
        fs::create_directories(dir_);
    }
    void TearDown() override {
        if (!keep_) fs::remove_all(dir_);
        test::VulkanTest::TearDown();
    }
    std::string write(const std::string& name, const std::string& bytes) const {
        std::ofstream(dir_ / name, std::ios::binary) << bytes;
        return (dir_ / name).string();
    }
    // `name`.glb and the scene file `name`.json that frames it: a camera above and in front, a
    // spot light above whose inner cone covers the floor.
    std::string writeScene(const std::string& name, const Gltf& gltf) const {
        write(name + ".glb", gltf.glb());
        const json scene = {
            {"gltf", name + ".glb"},
            {"light",
             {{"position", {0, 2, 0}},
              {"direction", {0, -1, 0}},
              {"intensity", 4},
              {"inner_cone_deg", 45},
              {"cone_deg", 60},
              {"radius", 0.02}}},
            {"camera", {{"position", {0, 2.4, 2.0}}, {"target", {0, 0, 0}}, {"yfov_deg", 50}}}};
        return write(name + ".json", scene.dump(2));
    }
    static Rendered renderBoth(const Scene& scene, const char* what) {
        Rendered r;
        r.frame = test::render(scene, kSize, kSize);
        reference::ReferenceOptions options;
        options.width = options.height = kSize;
        options.spp = 64;
        options.mode = reference::Mode::Direct;
        r.reference = reference::renderReference(scene, scene.camera, options).rgba;
        metrics::Mask geometry(r.frame.pixels());
        for (size_t i = 0; i < geometry.size(); ++i)
            r.geometryPixels += geometry[i] = r.frame.geometry(i);
        const metrics::Image a{kSize, kSize, r.frame.direct}, b{kSize, kSize, r.reference};
        r.relMse = metrics::errorFigures(a, b, geometry, metrics::ssimMap(a, b)).relMse;
        std::printf("%s: direct light relMSE against the path tracer %.5f over %zu pixels\n", what,
                    r.relMse, r.geometryPixels);
        return r;
    }
    fs::path dir_;
    bool keep_ = false;
};

// The mean colour of the direct light over the geometry pixels whose world x lies in [lo, hi].
inline glm::vec3 meanDirect(const test::Frame& f, float lo, float hi) {
    glm::dvec3 sum(0.0);
    size_t n = 0;
    for (size_t i = 0; i < f.pixels(); ++i) {
        const float x = f.position[4 * i];
        if (f.geometry(i) && x >= lo && x <= hi)
            sum += glm::dvec3(test::Frame::at(f.direct, i)), ++n;
    }
    return n ? glm::vec3(sum / double(n)) : glm::vec3(0.0f);
}

} // namespace ssgi::test
