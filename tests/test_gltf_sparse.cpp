// Sparse accessors (glTF 2.0 section 3.6.2.3) on small files the tests write themselves
// (gltf_files.h): for every attribute and for the indices, loaded as the dense file they stand
// for, rendered alike by both renderers, and refused with an error naming the problem where
// their indices or values do not fit.
#include "gltf_files.h"

#include <chrono>

#include <cstring>

using namespace ssgi;
using namespace ssgi::test;

namespace {

class GltfSparse : public GltfFiles {};

// Sparse accessors for every attribute and for the indices: POSITION and TEXCOORD_0 on no
// buffer view (zeros) with every element replaced, NORMAL and COLOR_0 on a dense base with some
// replaced, and the indices' second triangle made whole. The file must load as the dense file
// it stands for and render exactly as that file does.
TEST_F(GltfSparse, SparseAccessorsForEveryAttributeAndTheIndices) {
    Gltf dense = floorGltf();
    const std::vector<uint16_t> white(16, 65535);
    std::vector<uint16_t> colours = white;
    for (size_t v : {0, 3}) // red at the left corners
        colours[4 * v + 1] = colours[4 * v + 2] = 13107;
    dense.attribute("COLOR_0", colours, kUnsignedShort, "VEC4", 4, true);

    Gltf g;
    auto sparse = [&](int accessor, const std::vector<uint8_t>& indices, int values) {
        g.doc["accessors"][size_t(accessor)]["sparse"] = {
            {"count", indices.size()},
            {"indices", {{"bufferView", g.view(indices)}, {"componentType", kUnsignedByte}}},
            {"values", {{"bufferView", values}}}};
    };
    const int position = g.accessor(-1, kFloat, 4, "VEC3");
    sparse(position, {0, 1, 2, 3}, g.view(kCorners));
    const std::vector<float> tilted = {0, 1, 0, 0.6f, 0.8f, 0, 0.6f, 0.8f, 0, 0, 1, 0};
    const int normal = g.accessor(g.view(tilted), kFloat, 4, "VEC3");
    sparse(normal, {1, 2}, g.view(std::vector<float>{0, 1, 0, 0, 1, 0}));
    const int uv = g.accessor(-1, kFloat, 4, "VEC2");
    sparse(uv, {0, 1, 2, 3}, g.view(kUvs));
    const int colour = g.accessor(g.view(white), kUnsignedShort, 4, "VEC4", true);
    g.doc["accessors"][size_t(colour)]["normalized"] = true;
    sparse(colour, {0, 3},
           g.view(std::vector<uint16_t>{65535, 13107, 13107, 65535, 65535, 13107, 13107, 65535}));
    const std::vector<uint32_t> halfQuad = {0, 2, 1, 0, 0, 0};
    const int indices = g.accessor(g.view(halfQuad), kUnsignedInt, 6, "SCALAR");
    g.doc["accessors"][size_t(indices)]["sparse"] = {
        {"count", 2},
        {"indices",
         {{"bufferView", g.view(std::vector<uint16_t>{4, 5})}, {"componentType", kUnsignedShort}}},
        {"values", {{"bufferView", g.view(std::vector<uint32_t>{3, 2})}}}};
    g.primitive()["attributes"] = {
        {"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}, {"COLOR_0", colour}};
    g.primitive()["indices"] = indices;

    const Scene expected = loadScene(writeScene("dense", dense));
    const Scene scene = loadScene(writeScene("sparse", g));
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh &a = scene.meshes[0], &b = expected.meshes[0];
    EXPECT_EQ(a.indices, b.indices);
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    EXPECT_EQ(std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(Vertex)),
              0);
    EXPECT_TRUE(a.vertexColors);

    const Rendered r = renderBoth(scene, "sparse");
    EXPECT_LE(r.relMse, 0.01);
    EXPECT_GT(r.geometryPixels, kSize * kSize / 4);
    const test::Frame ofDense = test::render(expected, kSize, kSize);
    EXPECT_EQ(r.frame.direct, ofDense.direct); // the same scene model, the same image
    const glm::vec3 left = meanDirect(r.frame, -1.0f, -0.6f);
    EXPECT_GT(left.r, 3.0f * left.g);
}

// Sparse data is checked as any other: each case's error names the sparse accessor's problem.
TEST_F(GltfSparse, BadSparseAccessorsAreRefused) {
    struct Case {
        const char* name;
        json sparse;
        const char* message;
    };
    Gltf base = floorGltf();
    const int byteIndices = base.view(std::vector<uint8_t>{0, 7});
    const int shortIndices = base.view(std::vector<uint16_t>{0, 1});
    const int values = base.view(std::vector<float>{0, 0, 0, 1, 1, 1});
    const int twiceIndices = base.view(std::vector<uint8_t>{1, 1});
    auto sparse = [](int count, int indices, int type, int valueView, int valueOffset = 0) {
        return json{{"count", count},
                    {"indices", {{"bufferView", indices}, {"componentType", type}}},
                    {"values", {{"bufferView", valueView}, {"byteOffset", valueOffset}}}};
    };
    const Case cases[] = {
        {"index-out-of-range", sparse(2, byteIndices, kUnsignedByte, values),
         "sparse accessor: index 7 (entry 1) is out of range for 4 elements"},
        {"count-too-large", sparse(5, byteIndices, kUnsignedByte, values),
         "sparse accessor replaces 5 of 4 elements"},
        {"values-past-view", sparse(2, shortIndices, kUnsignedShort, values, 4),
         "sparse accessor values: 2 elements run past the end of buffer view"},
        {"missing-view", sparse(2, 99, kUnsignedShort, values),
         "sparse accessor indices: buffer view 99 does not exist"},
        {"float-indices", sparse(2, shortIndices, kFloat, values),
         "index component type 5126 is not an unsigned integer type"},
        // The later value won without a word.
        {"index-twice", sparse(2, twiceIndices, kUnsignedByte, values),
         "sparse accessor: index 1 appears twice (entries 0 and 1)"},
    };
    for (const Case& c : cases) {
        Gltf g = base;
        g.doc["accessors"][0]["sparse"] = c.sparse;
        const std::string path = write(std::string(c.name) + ".glb", g.glb());
        expectRefused(path, c.name, c.message);
    }
}

// An accessor without a buffer view holds zeros: its count is bounded by the data the file
// holds, refused at once (a small file asked for gigabytes, and ended in std::bad_alloc).
TEST_F(GltfSparse, ACountTheFileCannotHoldIsRefusedAtOnce) {
    Gltf g = floorGltf();
    const int indices = g.view(std::vector<uint32_t>{0, 1});
    const int values = g.view(std::vector<float>{0, 0, 0, 1, 1, 1});
    json& positions = g.doc["accessors"][0];
    positions.erase("bufferView");
    positions["count"] = 1000000000;
    positions["sparse"] = {{"count", 2},
                           {"indices", {{"bufferView", indices}, {"componentType", kUnsignedInt}}},
                           {"values", {{"bufferView", values}}}};
    const auto start = std::chrono::steady_clock::now();
    expectRefused(write("huge-count.glb", g.glb()), "huge-count",
                  "declares 1000000000 elements without a buffer view, more than the");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

} // namespace
