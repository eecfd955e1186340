// Numbers and files the loaders took or choked on: nesting that made the duplicate-key check
// quadratic, an unaligned accessor, a texture too large to decode, a path with a NUL; camera
// numbers inside the old ranges that broke the image; a glTF base colour above 1; path keys
// before time 0. Each is an InputError that names the problem, found in time linear in the file.
#include "bad_input.h"
#include "support.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace ssgi;
using namespace ssgi::test;

namespace {

json emptyBox() {
    std::ifstream in(test::sourcePath("tests/scenes/empty-box.json"));
    return json::parse(in);
}

class Parsers : public BadInput {
public:
    std::string writeFile(const std::string& name, const std::string& bytes) const {
        return write(name, bytes);
    }
};

// The one-triangle glTF with its JSON changed by `change`, written as NAME.glb.
template <class Change>
std::string changedGlb(const Parsers& test, const std::string& name, Change change) {
    json gltf = meshJson(kTriangle.size(), 3);
    std::string bin = meshBytes(kTriangle, {0, 1, 2});
    change(gltf, bin);
    return test.writeFile(name + ".glb", glb(gltf.dump(), bin));
}

TEST_F(Parsers, ParsersStayLinearAndNameTheProblem) {
    // 400 KB of nested arrays: refused at the nesting limit, at once.
    const size_t depth = 200000;
    const std::string deep =
        R"({"objects": )" + std::string(depth, '[') + std::string(depth, ']') + "}";
    const auto start = std::chrono::steady_clock::now();
    EXPECT_NE(loadError(write("deep.json", deep)).find("nested more than"), std::string::npos);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);

    // Positions two bytes into their buffer: floats that are not the file's.
    const std::string unaligned = changedGlb(*this, "unaligned", [](json& gltf, std::string& bin) {
        bin.insert(0, std::string(4, '\0'));
        gltf["buffers"][0]["byteLength"] = bin.size();
        gltf["bufferViews"][0]["byteOffset"] = 2;
        gltf["bufferViews"][1]["byteOffset"] = 40;
    });
    EXPECT_NE(loadError(unaligned).find("unaligned"), std::string::npos);

    // A valid PNG header of 100000x100000 pixels: the decoder refuses it, and says its size.
    std::string png = "\x89PNG\r\n\x1a\n";
    png += std::string("\0\0\0\x0dIHDR\0\x01\x86\xa0\0\x01\x86\xa0\x08\x02\0\0\0", 21);
    png += std::string(4, '\0') + std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12);
    write("big.png", png);
    json gltf = meshJson(kTriangle.size(), 3);
    gltf["buffers"][0]["uri"] = "mesh.bin";
    write("mesh.bin", meshBytes(kTriangle, {0, 1, 2}));
    gltf["images"] = {{{"uri", "big.png"}}};
    gltf["textures"] = {{{"source", 0}}};
    const std::string texture = write("texture.gltf", gltf.dump());
    EXPECT_NE(loadError(texture).find("PNG of 100000x100000 pixels"), std::string::npos);

    // A NUL inside a path would be read as the path before it.
    write("a", "");
    const std::string nul = write("nul.json", R"({"gltf": "a\u0000b.glb"})");
    EXPECT_NE(loadError(nul).find("NUL"), std::string::npos);
    gltf["buffers"][0]["uri"] = std::string("mesh.bin\0.png", 13);
    EXPECT_NE(loadError(write("nul.gltf", gltf.dump())).find("NUL"), std::string::npos);
}

// What the glTF specification refuses and tinygltf took, and tinygltf's refusals that named the
// wrong rule: an extensionsRequired that is not an array of names (rendered with exit 0, the
// required extension never looked at), a byteStride past 252 (refused as "must be the multiple
// of 4" when it was one), a data: URI without a media type (refused as "not a relative path").
TEST_F(Parsers, GltfRulesAreStatedAsTheSpecificationHasThem) {
    const std::pair<std::function<void(json&)>, std::string> cases[] = {
        {[](json& gltf) { gltf["extensionsRequired"] = "KHR_draco_mesh_compression"; },
         "extensionsRequired is \"KHR_draco_mesh_compression\", not an array of extension names"},
        {[](json& gltf) {
             gltf["extensionsRequired"] = {{"name", "EXT_x"}};
         },
         "extensionsRequired is {\"name\":\"EXT_x\"}, not an array of extension names"},
        {[](json& gltf) { gltf["extensionsRequired"] = {1}; },
         "extensionsRequired is [1], not an array of extension names"},
        {[](json& gltf) { gltf["extensionsUsed"] = "KHR_texture_transform"; },
         "extensionsUsed is \"KHR_texture_transform\", not an array"},
        {[](json& gltf) { gltf["bufferViews"][0]["byteStride"] = 256; },
         "buffer view 0: byteStride 256 is more than 252, the largest glTF allows"},
        {[](json& gltf) { gltf["bufferViews"][0]["byteStride"] = 14; },
         "buffer view 0: byteStride 14 is not a multiple of 4"},
        {[](json& gltf) { gltf["bufferViews"][1]["byteStride"] = 2; },
         "buffer view 1: byteStride 2 is less than 4, the smallest glTF allows"},
        {[](json& gltf) { gltf["buffers"][0]["uri"] = "data:;base64,AAAA"; },
         "data: URI 'data:;base64,AAAA' has no media type: an embedded buffer is "
         "data:application/octet-stream;base64,"},
        {[](json& gltf) { gltf["buffers"][0]["uri"] = "data:application/octet-stream,AAAA"; },
         "data: URI 'data:application/octet-stream,AAAA' is not base64"},
        {[](json& gltf) { gltf["buffers"][0]["uri"] = "data:text/csv;base64,AAAA"; },
         "data: URI 'data:text/csv;base64,AAAA' has the media type 'text/csv', which glTF does "
         "not embed"},
    };
    int i = 0;
    for (const auto& [change, expected] : cases) {
        const std::string file = changedGlb(*this, "case" + std::to_string(i++),
                                            [&](json& gltf, std::string&) { change(gltf); });
        SCOPED_TRACE(expected);
        EXPECT_NE(loadError(file).find(expected), std::string::npos) << loadError(file);
    }
    // A byteStride glTF allows, with an extensionsRequired of names, loads.
    const std::string fine = changedGlb(*this, "fine", [](json& gltf, std::string&) {
        gltf["bufferViews"][0]["byteStride"] = 12;
        gltf["extensionsUsed"] = {"KHR_lights_punctual"};
        gltf["extensionsRequired"] = {"KHR_lights_punctual"};
    });
    EXPECT_NO_THROW(loadScene(fine));
}

// Clip planes and fields of view inside the old ranges that drew nothing or broke the path
// tracer (an Embree assertion), and a glTF camera whose znear > zfar was "fixed" silently.
TEST_F(Parsers, CameraNumbersThatBreakTheImageAreRefused) {
    const std::pair<json, std::string> cameras[] = {
        {{{"near", 1e-9}}, "depth precision"},
        {{{"near", 100}, {"far", 200}}, "beyond the farthest point of the scene"},
        {{{"yfov_deg", 1e-9}}, "yfov_deg' is 1e-09, must be in [0.01"},
    };
    for (const auto& [change, message] : cameras) {
        json scene = emptyBox();
        scene["camera"].update(change);
        EXPECT_NE(loadError(write("camera.json", scene.dump())).find(message), std::string::npos)
            << change;
        // The same in a camera path's key.
        scene = emptyBox();
        json key = change;
        key["time"] = 0;
        scene["camera_path"] = {key};
        EXPECT_NE(loadError(write("path.json", scene.dump())).find(message), std::string::npos)
            << key;
    }
    const auto glbCamera = [&](double znear, double zfar, double yfov) {
        return changedGlb(*this, "camera", [&](json& gltf, std::string&) {
            gltf["cameras"] = {
                {{"type", "perspective"},
                 {"perspective", {{"yfov", yfov}, {"znear", znear}, {"zfar", zfar}}}}};
            gltf["nodes"].push_back({{"camera", 0}, {"translation", {0.3, 0.3, 2}}});
            gltf["scenes"][0]["nodes"].push_back(1);
        });
    };
    EXPECT_NE(loadError(glbCamera(10, 1, 0.8)).find("is not less than zfar"), std::string::npos);
    EXPECT_NE(loadError(glbCamera(0.1, 10, 1e-9)).find("narrower than"), std::string::npos);
    EXPECT_NO_THROW(loadScene(glbCamera(0.1, 10, 0.8)));
}

// One rule both ways in: an albedo above 1 reflects more light than it receives.
TEST_F(Parsers, AlbedoAboveOneIsRefusedInSceneFilesAndGltf) {
    json scene = emptyBox();
    scene["materials"]["white"]["albedo"] = {1.5, 0.5, 0.5};
    const std::string fileError = loadError(write("albedo.json", scene.dump()));
    EXPECT_NE(fileError.find("albedo' is 1.5, must be in [0, 1]"), std::string::npos) << fileError;
    const std::string gltf = changedGlb(*this, "albedo", [](json& gltf, std::string&) {
        gltf["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1.5, 0.5, 0.5, 1}}}}}};
        gltf["meshes"][0]["primitives"][0]["material"] = 0;
    });
    const std::string error = loadError(gltf);
    EXPECT_NE(error.find("material 0: baseColorFactor 1.5 is above 1"), std::string::npos) << error;
}

// The programs walk a path from time 0: a key before it would never be seen.
TEST_F(Parsers, PathKeysBeforeTimeZeroAreRefused) {
    json scene = emptyBox();
    scene["camera_path"] = {{{"time", -1}, {"position", {0, 0.5, -1.4}}},
                            {{"time", 1}, {"position", {0, 0.5, -1.2}}}};
    EXPECT_NE(loadError(write("early.json", scene.dump()))
                  .find("'camera_path[0].time' is -1, must be in [0,"),
              std::string::npos);
}

} // namespace
