// The world cache of indirect_method 3 (world_cache_pass.cpp, world_voxels_pass.cpp): its cells
// hold their value while only the camera moves, start over where the light or an object moved,
// keep their own values when their keys collide in the table, and keep them looked up at half
// resolution; the table follows the image. Its voxel grid: test_world_voxels.cpp.
#include "frame_uniforms.h"
#include "passes/passes.h"
#include "renderer.h"
#include "support.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

using namespace ssgi;

namespace {

constexpr uint32_t kSize = 48;

// The table as read back: each entry's key, irradiance (rgb, frames in a) and point (xyz).
struct Cells {
    std::vector<uint32_t> keys;
    std::vector<glm::vec4> irradiance;
    std::vector<glm::vec3> points;
    // Whether entry i holds a cell: a checksum is 2 or more, 0 an empty entry and 1 an evicted
    // one (world_cache.glsl), whose other texels hold anything.
    bool live(size_t i) const { return keys[i] > 1; }
};

Cells readCells(Renderer& renderer) {
    const std::vector<float> keys = renderer.readImage("world.keys");
    const std::vector<float> irradiance = renderer.readImage("world.irradiance");
    const std::vector<float> points = renderer.readImage("world.points");
    Cells cells;
    for (size_t i = 0; i < keys.size() / 4; ++i) {
        cells.keys.push_back(std::bit_cast<uint32_t>(keys[4 * i])); // texel_decode.h
        cells.irradiance.emplace_back(irradiance[4 * i], irradiance[4 * i + 1],
                                      irradiance[4 * i + 2], irradiance[4 * i + 3]);
        cells.points.emplace_back(points[4 * i], points[4 * i + 1], points[4 * i + 2]);
    }
    return cells;
}

class WorldCacheTest : public test::VulkanTest {
protected:
    Scene scene = [] {
        Scene s = loadScene(test::sourcePath("scenes/cornell-box.json"));
        s.settings.indirect_method = 3;
        return s;
    }();

    // A slow pan: a few pixels a frame at this size.
    Camera panned(int frame) const {
        Camera c = scene.camera;
        c.position.x += 0.004f * float(frame);
        return c;
    }
};

// Whether a cell that gathered at `before` may take `after` in its place (world_schedule.comp's
// retakes): at one of the levels beside the one at `after`'s distance from the camera
// (world_cache.glsl's worldLevel), both lie in the same cell and `after` lies nearer its centre
// than half `before`'s distance.
bool nearerTheCentre(glm::vec3 before, glm::vec3 after, const Camera& camera, float cellAngle) {
    const int level = int(std::floor(std::log2(glm::distance(after, camera.position) * cellAngle)));
    for (int l = level - 1; l <= level + 1; ++l) {
        const float side = std::exp2(float(l));
        const glm::vec3 cell = glm::floor(after / side);
        if (glm::floor(before / side) != cell) continue;
        const glm::vec3 centre = (cell + 0.5f) * side;
        if (glm::distance(after, centre) < 0.5f * glm::distance(before, centre)) return true;
    }
    return false;
}

// Once a cell holds world_frames frames of samples, the camera moving on changes nothing of it
// (the value is the surface's, looked up, not gathered again) unless its pixels offer a point
// much nearer its centre than the one it gathered at (a view that saw only its edge chose
// that): then it starts again there.
TEST_F(WorldCacheTest, AFullCellKeepsItsValueWhileTheCameraMovesUnlessItRetakes) {
    Renderer renderer(test::context(), scene, {kSize, kSize, "final"});
    const int frames = int(scene.settings.world_frames);
    for (int f = 0; f < frames + 8; ++f)
        renderer.renderFrame(panned(f));
    const Cells first = readCells(renderer);
    Cells before = first;
    int full = 0, retaken = 0;
    std::set<size_t> restarted;
    for (int f = frames + 8; f < frames + 16; ++f) {
        renderer.renderFrame(panned(f));
        const Cells after = readCells(renderer);
        for (size_t i = 0; i < before.keys.size(); ++i) {
            if (!first.live(i) || first.irradiance[i].a < float(frames)) continue;
            ASSERT_EQ(after.keys[i], before.keys[i]) << "entry " << i << " was evicted or taken";
            if (after.points[i] == before.points[i]) {
                // A retaken cell gathers again until it is full.
                if (!restarted.contains(i)) {
                    EXPECT_EQ(after.irradiance[i], before.irradiance[i]) << "entry " << i;
                }
                continue;
            }
            restarted.insert(i);
            ++retaken;
            EXPECT_TRUE(nearerTheCentre(before.points[i], after.points[i], panned(f),
                                        float(scene.settings.world_cell_angle)))
                << "entry " << i;
            EXPECT_EQ(after.irradiance[i].a, float(scene.settings.world_new_cell_frames))
                << "entry " << i << " retook its point without starting again";
        }
        before = after;
    }
    for (size_t i = 0; i < first.keys.size(); ++i)
        full += first.live(i) && first.irradiance[i].a >= float(frames);
    EXPECT_GT(full, 100) << "too few full cells to say anything";
    // The pan brings into view the middles of cells the first frames saw only at the image's
    // edge (9 of 2396 here), and retakes nothing else.
    std::printf("%d of %d full cells retook their point\n", retaken, full);
    EXPECT_GT(retaken, 0);
    EXPECT_LT(retaken, full / 20);
    const auto counts = renderer.worldCacheCounts();
    ASSERT_TRUE(counts.has_value());
    EXPECT_GT(counts->live, 0u);
}

// Every live cell of `after` holds a new cell's first gather alone (`newCellFrames` frames of
// samples), and a value other than `before`'s: the table restarted. Returns the live cells.
int expectEveryCellRestarted(const Cells& before, const Cells& after, float newCellFrames) {
    int live = 0, changed = 0;
    for (size_t i = 0; i < after.keys.size(); ++i) {
        if (!after.live(i)) continue;
        ++live;
        EXPECT_EQ(after.irradiance[i].a, newCellFrames) << "entry " << i;
        if (after.irradiance[i] != before.irradiance[i]) ++changed;
    }
    EXPECT_GT(live, 100);
    EXPECT_EQ(changed, live);
    return live;
}

// A moved light restarts every cell: the next frame each holds a new cell's first gather alone.
TEST_F(WorldCacheTest, AMovedLightRestartsEveryCell) {
    Renderer renderer(test::context(), scene, {kSize, kSize, "final"});
    for (int f = 0; f < 24; ++f)
        renderer.renderFrame(scene.camera);
    const Cells before = readCells(renderer);
    SpotLight light = renderer.light();
    light.position.x += 0.05f;
    renderer.setLight(light);
    renderer.renderFrame(scene.camera);
    const Cells after = readCells(renderer);
    const int live =
        expectEveryCellRestarted(before, after, float(scene.settings.world_new_cell_frames));
    const auto counts = renderer.worldCacheCounts();
    ASSERT_TRUE(counts.has_value());
    EXPECT_EQ(counts->filled, uint32_t(live));
    // A still frame after it refreshes without restarting: no cell goes back to a first
    // gather, and about as many gather one frame more as the frame's refreshes allow (a window
    // of the cells' hashes: world_schedule.comp; measured 1019 of 1309 for 1024).
    renderer.renderFrame(scene.camera);
    const Cells still = readCells(renderer);
    const float newCellFrames = float(scene.settings.world_new_cell_frames);
    int refreshed = 0;
    for (size_t i = 0; i < still.keys.size(); ++i) {
        if (!still.live(i)) continue;
        EXPECT_GE(still.irradiance[i].a, newCellFrames) << "entry " << i;
        refreshed += still.irradiance[i].a > newCellFrames;
    }
    const int budget = std::min(live, int(scene.settings.world_cells_per_frame));
    EXPECT_NEAR(refreshed, budget, 0.1 * budget);
}

// Which cells refresh when the frame's refreshes do not reach them all depends on the cells
// alone, not on the order the device's threads run in: two renderers of the same frames hold the
// same table bit for bit. (A budget handed out first come, first served made them differ.)
TEST_F(WorldCacheTest, TheRefreshesAreTheSameFromRunToRun) {
    Scene s = scene;
    s.settings.world_cells_per_frame = 64; // far fewer than the cells short of world_frames
    std::vector<Cells> runs;
    for (int run = 0; run < 2; ++run) {
        Renderer renderer(test::context(), s, {kSize, kSize, "final"});
        for (int f = 0; f < 8; ++f)
            renderer.renderFrame(panned(f));
        runs.push_back(readCells(renderer));
    }
    ASSERT_EQ(runs[0].keys.size(), runs[1].keys.size());
    int refreshedCells = 0;
    for (size_t i = 0; i < runs[0].keys.size(); ++i) {
        if (!runs[0].live(i)) continue;
        refreshedCells += runs[0].irradiance[i].a > float(s.settings.world_new_cell_frames);
    }
    EXPECT_GT(refreshedCells, 0);
    // The same cells may sit in other entries (an insert's probes race), so compare by key.
    std::map<uint32_t, glm::vec4> first;
    for (size_t i = 0; i < runs[0].keys.size(); ++i)
        if (runs[0].live(i)) first[runs[0].keys[i]] = runs[0].irradiance[i];
    size_t matched = 0;
    for (size_t i = 0; i < runs[1].keys.size(); ++i) {
        if (!runs[1].live(i)) continue;
        const auto it = first.find(runs[1].keys[i]);
        ASSERT_NE(it, first.end()) << "a key only the second run made";
        EXPECT_EQ(it->second, runs[1].irradiance[i]) << "key " << runs[1].keys[i];
        ++matched;
    }
    EXPECT_EQ(matched, first.size());
}

// A moved object restarts every cell, as a moved light does: each holds a new cell's first
// gather alone, and its value changed.
TEST_F(WorldCacheTest, AMovedObjectRestartsEveryCell) {
    Scene moving = loadScene(test::sourcePath("scenes/stability/moving-object.json"));
    moving.settings.indirect_method = 3;
    Renderer renderer(test::context(), moving, {kSize, kSize, "final"});
    renderer.setTime(0.0f);
    for (int f = 0; f < 24; ++f)
        renderer.renderFrame(moving.camera);
    const Cells before = readCells(renderer);
    renderer.setTime(1.0f);
    renderer.renderFrame(moving.camera);
    const Cells after = readCells(renderer);
    expectEveryCellRestarted(before, after, float(moving.settings.world_new_cell_frames));
}

// With a table of 4096 entries for about thirteen hundred cells, some two hundred keys share
// home entries and take the probes after them; every cell is still found and gathers what it
// would alone (its VPLs follow its key, not its entry), so the bounce is the same, bit for bit,
// as with 2^17 entries.
TEST_F(WorldCacheTest, CollidingKeysKeepTheirOwnValues) {
    scene.settings.cache = false;
    auto bounce = [&](int bits, Renderer::WorldCacheCounts& counts) {
        Scene s = scene;
        s.settings.world_table_bits = bits;
        Renderer renderer(test::context(), s, {kSize, kSize, "final"});
        renderer.renderFrame(s.camera);
        counts = *renderer.worldCacheCounts();
        return renderer.readImage("world.indirect");
    };
    Renderer::WorldCacheCounts small, large;
    const std::vector<float> crowded = bounce(12, small);
    const std::vector<float> roomy = bounce(17, large);
    EXPECT_EQ(small.entries, 4096u);
    EXPECT_EQ(small.full, 0u) << "every cell found an entry";
    EXPECT_EQ(small.live, large.live);
    EXPECT_GT(small.live, small.entries / 5) << "too few cells for keys to collide";
    ASSERT_EQ(crowded.size(), roomy.size());
    size_t lit = 0;
    for (size_t i = 0; i < crowded.size(); ++i) {
        ASSERT_EQ(crowded[i], roomy[i]) << "texel " << i / 4;
        lit += crowded[i] > 0.0f;
    }
    EXPECT_GT(lit, crowded.size() / 4);
}

// The bounce of a renderer with world_half_res against one without, on the same cells: the
// pixels looked up alone (world.edge_list, `listed`) hold the full-resolution lookup's value bit
// for bit, the others lie close to it (their RMS difference, relative to the full lookup's mean,
// is returned), and none is dark where the full lookup is lit. A pixel that holds a sample (the
// top-left one of its block) takes that sample's value all but alone (its neighbours weigh 1e-4
// each, half_resolution.glsl): the same as the full lookup's to a half float's rounding.
double expectHalfResolutionAgrees(const std::vector<float>& full, const std::vector<float>& half,
                                  const std::vector<uint32_t>& listed, uint32_t size) {
    EXPECT_GT(listed.size(), 0u) << "no pixel looked up alone: the edges' rule was not tested";
    EXPECT_LT(listed.size(), size * size / 8);
    std::vector<bool> alone(size * size, false);
    for (uint32_t pixel : listed) {
        if (pixel >= size * size) {
            ADD_FAILURE() << "listed pixel " << pixel << " outside the image";
            continue;
        }
        alone[pixel] = true;
        for (int c = 0; c < 4; ++c)
            EXPECT_EQ(half[4 * pixel + c], full[4 * pixel + c]) << "pixel " << pixel;
    }
    double squared = 0.0, value = 0.0;
    size_t interpolated = 0, sampled = 0;
    for (size_t i = 0; i < size_t(size) * size; ++i) {
        const float f = full[4 * i] + full[4 * i + 1] + full[4 * i + 2];
        const float h = half[4 * i] + half[4 * i + 1] + half[4 * i + 2];
        if (alone[i] || f == 0.0f) continue;
        EXPECT_GT(h, 0.0f) << "pixel " << i << " dark";
        if ((i % size) % 2 == 0 && (i / size) % 2 == 0) {
            EXPECT_NEAR(h, f, 2e-3f * f) << "pixel " << i << " holds a sample";
            ++sampled;
        }
        squared += double(h - f) * double(h - f);
        value += double(f);
        ++interpolated;
    }
    EXPECT_GT(interpolated, size_t(size) * size / 2);
    EXPECT_GT(sampled, interpolated / 5);
    const double mean = value / double(std::max<size_t>(interpolated, 1));
    const double relativeRms =
        std::sqrt(squared / double(std::max<size_t>(interpolated, 1))) / mean;
    std::printf("%zu pixels looked up alone, %zu interpolated: RMS difference %.4f of the mean\n",
                listed.size(), interpolated, relativeRms);
    return relativeRms;
}

// The pixels world.upsample listed for world.lookup_edges in the last frame.
std::vector<uint32_t> pixelsLookedUpAlone(Renderer& renderer) {
    const uint32_t count = renderer.worldCacheCounts()->edges;
    const std::vector<float> list = renderer.readImage("world.edge_list");
    std::vector<uint32_t> listed;
    for (uint32_t i = 0; i < count && 4 * i < list.size(); ++i)
        listed.push_back(std::bit_cast<uint32_t>(list[4 * i]));
    return listed;
}

// With world_half_res the lookup runs at the top-left pixel of every 2x2 block, and each pixel
// interpolates the samples on its surface around it; a pixel with none is looked up alone by the
// full-resolution rule. Every pixel still finds or makes its own cell, so the cells are those of
// a full-resolution renderer: one uncached frame of each agrees as expectHalfResolutionAgrees
// says (7.6% RMS measured).
TEST_F(WorldCacheTest, HalfResolutionLookupKeepsTheFullOnesValues) {
    scene.settings.cache = false;
    constexpr uint32_t size = 96;
    Scene halfScene = scene;
    halfScene.settings.world_half_res = true;
    Renderer full(test::context(), scene, {size, size, "final"});
    Renderer half(test::context(), halfScene, {size, size, "final", {"world.edge_list"}});
    full.renderFrame(scene.camera);
    half.renderFrame(scene.camera);
    EXPECT_EQ(half.worldCacheCounts()->live, full.worldCacheCounts()->live) << "the same cells";
    EXPECT_EQ(full.worldCacheCounts()->edges, 0u);
    EXPECT_LT(expectHalfResolutionAgrees(full.readImage("world.indirect"),
                                         half.readImage("world.indirect"),
                                         pixelsLookedUpAlone(half), size),
              0.1);
}

// The same along a pan with the cache on, every frame: the list of pixels looked up alone and its
// indirect dispatch are made anew each frame (their counters alternate rows with the frame's
// parity). Every cell refreshes each frame (world_cells_per_frame beyond the cells), so that
// both renderers' cells hold the same values whatever order the threads take them in.
TEST_F(WorldCacheTest, HalfResolutionLookupKeepsTheFullOnesValuesWhileTheCameraPans) {
    scene.settings.world_cells_per_frame = 1 << 20;
    constexpr uint32_t size = 96;
    Scene halfScene = scene;
    halfScene.settings.world_half_res = true;
    Renderer full(test::context(), scene, {size, size, "final"});
    Renderer half(test::context(), halfScene, {size, size, "final", {"world.edge_list"}});
    for (int f = 0; f < 6; ++f) {
        full.renderFrame(panned(4 * f));
        half.renderFrame(panned(4 * f));
        SCOPED_TRACE("frame " + std::to_string(f));
        EXPECT_EQ(half.worldCacheCounts()->live, full.worldCacheCounts()->live);
        EXPECT_LT(expectHalfResolutionAgrees(full.readImage("world.indirect"),
                                             half.readImage("world.indirect"),
                                             pixelsLookedUpAlone(half), size),
                  0.1);
    }
}

} // namespace

namespace {

// The table follows the image: 2^bits entries at or above half its pixels, between 2^14 and
// 2^18, unless world_table_bits names its size; and the table a renderer makes is that size.
TEST(WorldCacheTable, IsSizedFromTheImage) {
    Settings settings;
    ASSERT_EQ(settings.world_table_bits, 0);
    EXPECT_EQ(worldTableBits(settings, {96, 72}), 14);
    EXPECT_EQ(worldTableBits(settings, {256, 256}), 15);
    EXPECT_EQ(worldTableBits(settings, {512, 512}), 17);
    EXPECT_EQ(worldTableBits(settings, {1920, 1080}), 18);
    settings.world_table_bits = 9;
    EXPECT_EQ(worldTableBits(settings, {1920, 1080}), 9);
    Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    scene.settings.indirect_method = 3;
    Renderer renderer(test::context(), scene, {256, 256, "final"});
    renderer.renderFrame(scene.camera);
    const auto counts = renderer.worldCacheCounts();
    ASSERT_TRUE(counts.has_value());
    EXPECT_EQ(counts->entries, 1u << 15);
}

} // namespace
