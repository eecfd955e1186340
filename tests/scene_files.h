// What the scene-loading tests share (test_scene.cpp, test_bare_models.cpp): glTF files written
// by hand with known answers, and a fixture that writes files into a fresh folder and expects
// loading to fail with a message naming the file and every given detail.
#pragma once

#include "scene/bare_model.h"
#include "scene/camera.h"
#include "scene/scene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace fs = std::filesystem;
using nlohmann::json;
using ssgi::InputError;
using ssgi::loadScene;
using ssgi::Scene;

namespace scene_files {

const std::string kSourceDir = SSGI_SOURCE_DIR;
const std::string kModels = kSourceDir + "/scenes/models/";

inline std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t group = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) group |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) group |= bytes[i + 2];
        for (size_t k = 0; k < 4; ++k)
            out += i + k <= bytes.size() ? digits[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

// A glTF with one indexed triangle-list mesh (no normals) in an embedded base64 buffer.
inline json triangleGltf(const std::vector<float>& positions, const std::vector<uint16_t>& indices,
                         const json& nodes, const json& rootNodes) {
    std::vector<uint8_t> bytes(positions.size() * 4 + indices.size() * 2);
    std::memcpy(bytes.data(), positions.data(), positions.size() * 4);
    std::memcpy(bytes.data() + positions.size() * 4, indices.data(), indices.size() * 2);
    const size_t positionBytes = positions.size() * 4;
    return {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", rootNodes}}}},
        {"nodes", nodes},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
        {"buffers",
         {{{"byteLength", bytes.size()},
           {"uri", "data:application/octet-stream;base64," + base64(bytes)}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", positionBytes}},
          {{"buffer", 0}, {"byteOffset", positionBytes}, {"byteLength", indices.size() * 2}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", positions.size() / 3},
           {"type", "VEC3"}},
          {{"bufferView", 1},
           {"componentType", 5123},
           {"count", indices.size()},
           {"type", "SCALAR"}}}},
    };
}

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

class SceneFiles : public ::testing::Test {
protected:
    void SetUp() override {
        std::random_device random;
        dir_ = fs::temp_directory_path() / ("ssgi_test_scene_" + std::to_string(random()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& text) const {
        const std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
    // Loading must fail with an InputError naming the file and every given detail.
    void expectInputError(const std::string& path, const std::vector<std::string>& details) {
        try {
            loadScene(path);
            ADD_FAILURE() << path << " loaded, expected an InputError";
        } catch (const InputError& error) {
            const std::string message = error.what();
            EXPECT_NE(message.find(fs::path(path).filename().string()), std::string::npos)
                << message;
            for (const std::string& detail : details)
                EXPECT_NE(message.find(detail), std::string::npos)
                    << "'" << detail << "' not in: " << message;
        }
    }
    // A scene file of one white quad plus `extra` top-level keys.
    std::string quadScene(const std::string& name, const json& extra) const {
        json scene = {{"materials", {{"white", {{"albedo", {0.8, 0.8, 0.8}}}}}},
                      {"objects",
                       {{{"type", "quad"},
                         {"material", "white"},
                         {"corners", {{1, 0, 0}, {0, 0, 0}, {0, 0, 1}, {1, 0, 1}}}}}}};
        scene.update(extra);
        return write(name, scene.dump());
    }

    fs::path dir_;
};

} // namespace scene_files

using namespace scene_files;
