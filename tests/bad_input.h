// What the bad-input tests share: a one-triangle glTF to change into hostile ones, and a fixture
// with a private temporary folder.
#pragma once

#include "scene/scene.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

namespace ssgi::test {

// The binary chunk of a one-mesh glTF: float positions, then 32-bit indices.
inline std::string meshBytes(const std::vector<float>& positions,
                             const std::vector<uint32_t>& indices) {
    std::string bytes(positions.size() * 4 + indices.size() * 4, '\0');
    std::memcpy(bytes.data(), positions.data(), positions.size() * 4);
    std::memcpy(bytes.data() + positions.size() * 4, indices.data(), indices.size() * 4);
    return bytes;
}

// The JSON of that glTF: one indexed triangle list in node 0 of scene 0.
inline nlohmann::json meshJson(size_t positionCount, size_t indexCount) {
    const size_t positionBytes = positionCount * 4, indexBytes = indexCount * 4;
    auto accessor = [](int view, int type, size_t count, const char* shape) {
        return nlohmann::json{
            {"bufferView", view}, {"componentType", type}, {"count", count}, {"type", shape}};
    };
    return {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
        {"buffers", {{{"byteLength", positionBytes + indexBytes}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteLength", positionBytes}},
          {{"buffer", 0}, {"byteOffset", positionBytes}, {"byteLength", indexBytes}}}},
        {"accessors",
         {accessor(0, 5126, positionCount / 3, "VEC3"), accessor(1, 5125, indexCount, "SCALAR")}}};
}

// GLB container: 12-byte header, JSON chunk (space padded), BIN chunk (zero padded).
inline std::string glb(const std::string& text, std::string bin) {
    const std::string padded = text + std::string((4 - text.size() % 4) % 4, ' ');
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const uint32_t length = uint32_t(28 + padded.size() + bin.size());
    return "glTF" + u32(2) + u32(length) + u32(uint32_t(padded.size())) + "JSON" + padded +
           u32(uint32_t(bin.size())) + "BIN" + std::string(1, '\0') + bin;
}
inline std::string meshGlb(const std::vector<float>& positions,
                           const std::vector<uint32_t>& indices) {
    return glb(meshJson(positions.size(), indices.size()).dump(), meshBytes(positions, indices));
}
inline const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

class BadInput : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ =
            std::filesystem::temp_directory_path() / ("ssgi-bad-input-" + std::to_string(getpid()) +
                                                      "-" + std::to_string(std::random_device()()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string write(const std::string& name, const std::string& bytes) const {
        std::ofstream(dir_ / name, std::ios::binary) << bytes;
        return (dir_ / name).string();
    }
    // The message of the InputError loading `path` throws; fails the test when it loads.
    static std::string loadError(const std::string& path) {
        try {
            loadScene(path);
        } catch (const InputError& error) {
            return error.what();
        }
        ADD_FAILURE() << path << " loaded; an InputError was expected";
        return "";
    }
    std::filesystem::path dir_;
};

} // namespace ssgi::test
