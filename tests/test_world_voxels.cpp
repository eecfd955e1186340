// The world cache's voxel grid (world_voxels_pass.cpp), read back: it blocks the segments the
// scene's triangles block and leaves open those they leave open.
#include "frame_uniforms.h"
#include "passes/passes.h"
#include "renderer.h"
#include "support.h"

#include <bit>

using namespace ssgi;

namespace {

class WorldVoxelsTest : public test::VulkanTest {};

// The voxel grid as drawn blocks the segments the scene's triangles block: one through the tall
// block, from the floor in front of it to the back wall behind it, and one across the open box,
// from the floor to the ceiling beside the blocks. Each segment's ends lie on surfaces, as the
// cells' and the VPLs' do; their own voxels (within two voxels of each end) are left out, as
// the visibility test leaves them (world_voxels.glsl).
TEST_F(WorldVoxelsTest, TheGridBlocksWhatTheTrianglesBlock) {
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    scene.settings.indirect_method = 3;
    Renderer renderer(test::context(), scene, {48, 48, "final"});
    renderer.renderFrame(scene.camera);
    const std::vector<float> words = renderer.readImage("world.voxels");
    const WorldGridPlacement& grid = renderer.worldGrid();
    const glm::dvec3 origin = gpuOrigin(scene.bounds);
    // The images hold the largest grid, in 4 x 4 x 4 blocks of two texels (world_voxels.glsl).
    const int blocks = (int(scene.settings.world_voxels) + WORLD_BLOCK - 1) / WORLD_BLOCK;
    const uint32_t width = uint32_t(2 * blocks * blocks);
    const int rowBlocks = (grid.size.x + WORLD_BLOCK - 1) / WORLD_BLOCK;
    ASSERT_EQ(words.size(), size_t(4) * width * uint32_t(blocks));
    auto occupied = [&](glm::ivec3 v) {
        if (glm::any(glm::lessThan(v, glm::ivec3(0))) ||
            glm::any(glm::greaterThanEqual(v, grid.size)))
            return false;
        const glm::ivec3 b = v / WORLD_BLOCK, local = v % WORLD_BLOCK;
        const size_t texel =
            size_t(b.y) * width + size_t(2 * (b.x + rowBlocks * b.z)) + size_t(local.z >> 1);
        const int bit = local.x + 4 * local.y + 16 * (local.z & 1);
        return ((std::bit_cast<uint32_t>(words[4 * texel]) >> bit) & 1u) != 0u;
    };
    auto gridBlocks = [&](glm::vec3 a, glm::vec3 b) {
        const float voxel = grid.voxel;
        const glm::vec3 lo = grid.origin;
        const glm::vec3 A = (moved(a, origin) - lo) / voxel, B = (moved(b, origin) - lo) / voxel;
        const float length = glm::length(B - A);
        for (float s = 2.0f; s < length - 2.0f; s += 0.125f)
            if (occupied(glm::ivec3(glm::floor(A + (B - A) * (s / length))))) return true;
        return false;
    };
    const glm::vec3 frontFloor(0.37f, 0.0f, 0.05f), backWall(0.37f, 0.2f, 0.5592f);
    const glm::vec3 openFloor(0.45f, 0.0f, 0.10f), ceiling(0.45f, 0.5488f, 0.12f);
    ASSERT_TRUE(test::segmentBlocked(scene, frontFloor, backWall));
    ASSERT_FALSE(test::segmentBlocked(scene, openFloor, ceiling));
    EXPECT_TRUE(gridBlocks(frontFloor, backWall));
    EXPECT_FALSE(gridBlocks(openFloor, ceiling));
}

} // namespace
