// glTF as exporters write it, on small files the tests write themselves (gltf_files.h): vertex
// colours, texture samplers, one-sided surfaces and morph targets' warning. Each file is loaded,
// rendered by the real-time renderer and path-traced, and the two direct-light images compared;
// beside that, each feature is checked against what glTF says it means.
#include "gltf_files.h"
#include "image_io.h"

#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <sstream>

using namespace ssgi;
using namespace ssgi::test;

namespace {

class GltfFeatures : public GltfFiles {};

// glTF multiplies COLOR_0 into the base colour: the floor's left half red, its right half green,
// in each of the encodings glTF allows, exactly decoded and drawn alike by both renderers.
TEST_F(GltfFeatures, VertexColoursMultiplyTheBaseColour) {
    const glm::vec3 red(0.8f, 0.15f, 0.1f), green(0.1f, 0.7f, 0.2f);
    const std::array<glm::vec3, 4> corner = {red, green, green, red};
    struct Encoding {
        const char* name;
        int componentType;
        int components;
    };
    for (const Encoding e :
         {Encoding{"float-rgb", kFloat, 3}, Encoding{"ubyte-rgba", kUnsignedByte, 4},
          Encoding{"ushort-rgba", kUnsignedShort, 4}}) {
        SCOPED_TRACE(e.name);
        Gltf g = floorGltf();
        std::vector<float> floats;
        std::vector<uint8_t> bytes;
        std::vector<uint16_t> shorts;
        std::vector<glm::u16vec4> expected;
        for (const glm::vec3& c : corner) {
            glm::u16vec4 decoded(65535);
            for (int k = 0; k < e.components; ++k) {
                const float v = k < 3 ? c[k] : 1.0f;
                floats.push_back(v);
                bytes.push_back(uint8_t(std::lround(v * 255.0f)));
                shorts.push_back(uint16_t(std::lround(v * 65535.0f)));
                decoded[k] =
                    e.componentType == kUnsignedByte ? uint16_t(bytes.back() * 257) : shorts.back();
            }
            expected.push_back(decoded);
        }
        const char* type = e.components == 3 ? "VEC3" : "VEC4";
        if (e.componentType == kFloat) g.attribute("COLOR_0", floats, kFloat, type, 3);
        if (e.componentType == kUnsignedByte)
            g.attribute("COLOR_0", bytes, kUnsignedByte, type, 4, true);
        if (e.componentType == kUnsignedShort)
            g.attribute("COLOR_0", shorts, kUnsignedShort, type, 4, true);
        const Scene scene = loadScene(writeScene(std::string("colours-") + e.name, g));
        ASSERT_EQ(scene.meshes.size(), 1u);
        const Mesh& mesh = scene.meshes[0];
        EXPECT_TRUE(mesh.vertexColors);
        for (size_t v = 0; v < 4; ++v)
            EXPECT_EQ(mesh.vertices[v].color, expected[v]) << "vertex " << v;

        const Rendered r = renderBoth(scene, e.name);
        EXPECT_LE(r.relMse, 0.01);
        EXPECT_GT(r.geometryPixels, kSize * kSize / 4);
        // Red where the red corners are, green where the green ones are.
        const glm::vec3 left = meanDirect(r.frame, -1.0f, -0.6f);
        const glm::vec3 right = meanDirect(r.frame, 0.6f, 1.0f);
        EXPECT_GT(left.r, 3.0f * left.g);
        EXPECT_GT(right.g, 3.0f * right.r);
    }
}

// A 2 x 2 texture over the floor's uv from -1 to 2, under three samplers: each axis's wrap mode
// and the nearest or bilinear filter as glTF says, the same in both renderers. Where the filter
// is nearest, every G-buffer albedo away from a texel's edge is the texel glTF's rule picks.
TEST_F(GltfFeatures, SamplersWrapAndFilterAsGltfSays) {
    const uint8_t texels[2][2][3] = {{{200, 120, 60}, {60, 200, 120}},
                                     {{120, 60, 200}, {180, 180, 180}}}; // [row][column]
    std::vector<float> rgba;
    for (const auto& row : texels)
        for (const auto& texel : row)
            rgba.insert(rgba.end(), {texel[0] / 255.0f, texel[1] / 255.0f, texel[2] / 255.0f, 1});
    writeImage((dir_ / "texture.png").string(), 2, 2, rgba);
    auto linear = [](uint8_t c) {
        const float v = c / 255.0f;
        return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
    };
    constexpr int kRepeat = 10497, kClamp = 33071, kMirror = 33648, kNearest = 9728, kLinear = 9729;
    // glTF's rule for the texel a coordinate t (in texels) of an axis of 2 falls in.
    auto texelOf = [](float t, int wrap) {
        const int i = int(std::floor(t));
        if (wrap == kClamp) return std::clamp(i, 0, 1);
        if (wrap == kRepeat) return ((i % 2) + 2) % 2;
        const int k = ((i % 4) + 4) % 4;
        return k < 2 ? k : 3 - k;
    };
    struct Sampler {
        const char* name;
        int wrapS, wrapT, filter;
    };
    for (const Sampler& sampler : {Sampler{"clamp-mirror-nearest", kClamp, kMirror, kNearest},
                                   Sampler{"mirror-repeat-nearest", kMirror, kRepeat, kNearest},
                                   Sampler{"mirror-clamp-linear", kMirror, kClamp, kLinear}}) {
        SCOPED_TRACE(sampler.name);
        Gltf g = floorGltf();
        g.doc["images"] = {{{"uri", "texture.png"}}};
        g.doc["samplers"] = {{{"wrapS", sampler.wrapS},
                              {"wrapT", sampler.wrapT},
                              {"magFilter", sampler.filter},
                              {"minFilter", sampler.filter}}};
        g.doc["textures"] = {{{"source", 0}, {"sampler", 0}}};
        g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
        const Scene scene = loadScene(writeScene(sampler.name, g));
        const Rendered r = renderBoth(scene, sampler.name);
        EXPECT_LE(r.relMse, 0.01);
        EXPECT_GT(r.geometryPixels, kSize * kSize / 4);
        if (sampler.filter != kNearest) continue;
        size_t checked = 0, right = 0;
        for (size_t i = 0; i < r.frame.pixels(); ++i) {
            if (!r.frame.geometry(i)) continue;
            const glm::vec3 p = test::Frame::at(r.frame.position, i);
            const float s = 2.0f * (-1.0f + 1.5f * (p.x + 1.0f)); // in texels
            const float t = 2.0f * (-1.0f + 1.5f * (p.z + 1.0f));
            auto nearEdge = [](float c) { return std::abs(c - std::round(c)) < 0.05f; };
            if (nearEdge(s) || nearEdge(t)) continue;
            const auto& texel = texels[texelOf(t, sampler.wrapT)][texelOf(s, sampler.wrapS)];
            const glm::vec3 albedo = test::Frame::at(r.frame.albedo, i);
            ++checked;
            right += std::abs(albedo.r - linear(texel[0])) < 0.01f &&
                     std::abs(albedo.g - linear(texel[1])) < 0.01f &&
                     std::abs(albedo.b - linear(texel[2])) < 0.01f;
        }
        EXPECT_GT(checked, r.geometryPixels / 2);
        EXPECT_GE(double(right), 0.99 * double(checked)) << right << " of " << checked;
    }
}

// The scene model's surfaces are two-sided whatever glTF's doubleSided says (scene-files.md): a
// floor facing down, doubleSided false, seen and lit from above is drawn and lit in both
// renderers exactly as the same floor marked doubleSided true, with one warning.
TEST_F(GltfFeatures, SingleSidedSurfacesAreDrawnTwoSided) {
    auto facingDown = [](bool doubleSided) {
        Gltf g;
        g.attribute("POSITION", kCorners, kFloat, "VEC3", 3);
        g.attribute("NORMAL", std::vector<float>{0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1, 0}, kFloat,
                    "VEC3", 3);
        const std::vector<uint32_t> down = {0, 1, 2, 0, 2, 3}; // counter-clockwise from below
        g.primitive()["indices"] = g.accessor(g.view(down), kUnsignedInt, 6, "SCALAR");
        g.doc["materials"][0]["doubleSided"] = doubleSided;
        return g;
    };
    const Scene twoSided = loadScene(writeScene("double-sided", facingDown(true)));
    std::ostringstream said;
    std::streambuf* saved = std::cerr.rdbuf(said.rdbuf());
    const Scene oneSided = loadScene(writeScene("single-sided", facingDown(false)));
    std::cerr.rdbuf(saved);
    const std::string warning = "doubleSided false is drawn two-sided";
    const size_t first = said.str().find(warning);
    EXPECT_NE(first, std::string::npos) << said.str();
    EXPECT_EQ(said.str().find(warning, first + 1), std::string::npos) << said.str();

    const Rendered r = renderBoth(oneSided, "single-sided");
    EXPECT_LE(r.relMse, 0.01);
    EXPECT_GT(r.geometryPixels, kSize * kSize / 4);
    EXPECT_EQ(r.frame.direct, test::render(twoSided, kSize, kSize).direct);
    for (size_t i = 0; i < r.frame.pixels(); ++i)
        if (r.frame.geometry(i)) {
            ASSERT_GT(r.frame.normal[4 * i + 1], 0.99f) << "pixel " << i; // toward the camera
            ASSERT_GT(test::Frame::luminance(r.frame.direct, i), 0.0f) << "pixel " << i;
        }
}

// Morph targets are ignored with a warning that says the default weights are not applied.
TEST_F(GltfFeatures, MorphTargetsWarnAboutTheirDefaultWeights) {
    Gltf g = floorGltf();
    const int offsets = g.accessor(g.view(std::vector<float>(12, 0.5f)), kFloat, 4, "VEC3");
    g.primitive()["targets"] = {{{"POSITION", offsets}}};
    g.doc["meshes"][0]["weights"] = {1.0};
    std::ostringstream said;
    std::streambuf* saved = std::cerr.rdbuf(said.rdbuf());
    const Scene scene = loadScene(writeScene("morph", g));
    std::cerr.rdbuf(saved);
    EXPECT_NE(said.str().find("morph targets are ignored: the base shape is drawn, without the "
                              "mesh's default morph weights"),
              std::string::npos)
        << said.str();
    EXPECT_EQ(scene.meshes.at(0).vertices.at(2).position, glm::vec3(1, 0, 1)); // the base shape
}

// Extensions the loader does not read are named in a warning, each once: the picture differs
// from what the file means (a texture's scale, a compressed mesh).
TEST_F(GltfFeatures, IgnoredExtensionsAreNamed) {
    Gltf g = floorGltf();
    g.doc["extensionsUsed"] = {"KHR_texture_transform", "KHR_draco_mesh_compression"};
    g.doc["materials"][0]["pbrMetallicRoughness"]["extensions"] = {
        {"KHR_texture_transform", {{"scale", {2, 2}}}}};
    g.primitive()["extensions"] = {{"EXT_unknown_thing", json::object()}};
    std::ostringstream said;
    std::streambuf* saved = std::cerr.rdbuf(said.rdbuf());
    loadScene(writeScene("extensions", g));
    std::cerr.rdbuf(saved);
    for (const char* expected : {"extension KHR_texture_transform is ignored",
                                 "extension KHR_draco_mesh_compression is ignored",
                                 "extension EXT_unknown_thing is ignored"})
        EXPECT_NE(said.str().find(expected), std::string::npos) << said.str();
}

// Colours and samplers glTF does not define are bad input, named with their problem.
TEST_F(GltfFeatures, BadColoursAndSamplersAreRefused) {
    struct Case {
        const char* name;
        std::function<void(Gltf&)> change;
        const char* message;
    };
    auto textured = [](Gltf& g, const json& sampler) {
        // A white 1 x 1 PNG.
        g.doc["images"] = {{{"uri", "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAf"
                                    "FcSJAAAAC0lEQVR4nGP4DwQACfsD/fteaysAAAAASUVORK5CYII="}}};
        g.doc["samplers"] = {sampler};
        g.doc["textures"] = {{{"source", 0}, {"sampler", 0}}};
        g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    };
    const Case cases[] = {
        {"colour-above-one",
         [](Gltf& g) {
             g.attribute("COLOR_0", std::vector<float>{0, 0, 0, 1, 1, 1, 2, 0, 0, 1, 1, 1}, kFloat,
                         "VEC3", 3);
         },
         "COLOR_0 2 is not within [0, 1]"},
        {"colour-nan",
         [](Gltf& g) {
             g.attribute("COLOR_0", std::vector<float>(12, std::nanf("")), kFloat, "VEC3", 3);
         },
         "COLOR_0 0 is not within [0, 1]"},
        {"wrap",
         [&](Gltf& g) {
             textured(g, {{"wrapS", 1234}});
         },
         "sampler 0: wrapS 1234 is not a glTF wrap mode"},
        {"mag-filter",
         [&](Gltf& g) {
             textured(g, {{"magFilter", 9984}});
         },
         "sampler 0: magFilter 9984 is not a glTF magnification filter"},
        {"missing-sampler",
         [&](Gltf& g) {
             textured(g, json::object());
             g.doc["textures"][0]["sampler"] = 3;
         },
         "texture 0 refers to sampler 3, which does not exist"},
        // tinygltf took these as REPEAT, as the int they were cut to, or as "none".
        {"wrap-as-string",
         [&](Gltf& g) {
             textured(g, {{"wrapS", "CLAMP_TO_EDGE"}});
         },
         "sampler 0: wrapS \"CLAMP_TO_EDGE\" is not a glTF wrap mode (a whole number)"},
        {"wrap-fraction",
         [&](Gltf& g) {
             textured(g, {{"wrapT", 33071.5}});
         },
         "sampler 0: wrapT 33071.5 is not a glTF wrap mode"},
        {"wrap-beyond-32-bits",
         [&](Gltf& g) {
             textured(g, {{"wrapS", 33071 + 4294967296}});
         },
         "sampler 0: wrapS 4295000367 is not a glTF wrap mode"},
        {"negative-sampler",
         [&](Gltf& g) {
             textured(g, json::object());
             g.doc["textures"][0]["sampler"] = -1;
         },
         "texture 0: sampler -1 is not an index (0 or more)"},
        {"negative-texture",
         [&](Gltf& g) {
             textured(g, json::object());
             g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = -2;
         },
         "material 0 baseColorTexture: index -2 is not an index"},
        {"alpha-mode", [](Gltf& g) { g.doc["materials"][0]["alphaMode"] = "bogus"; },
         "material 0: alphaMode \"bogus\" is not OPAQUE, MASK or BLEND"},
        {"negative-mesh", [](Gltf& g) { g.doc["nodes"][0]["mesh"] = -1; },
         "node 0: mesh -1 is not an index (0 or more)"},
        {"fractional-mode", [](Gltf& g) { g.primitive()["mode"] = 4.5; },
         "mesh 0 primitive 0: mode 4.5 is not a glTF primitive mode"},
    };
    for (const Case& c : cases) {
        Gltf g = floorGltf();
        c.change(g);
        const std::string path = write(std::string(c.name) + ".glb", g.glb());
        expectRefused(path, c.name, c.message);
    }
}

} // namespace
