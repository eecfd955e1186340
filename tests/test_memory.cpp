// Memory over long runs: a renderer drawing thousands of frames holds what it held after its
// first few hundred. On lavapipe device memory is host memory, so resident memory counts
// leaked images, buffers and driver state alike (a driver recompiling a shader at every
// dispatch and keeping each copy grew the process with every frame).
#include "renderer.h"
#include "scene/camera.h"
#include "support.h"

#include <fstream>
#include <string>

using namespace ssgi;

namespace {

// The process's resident memory in MiB (VmRSS of /proc/self/status).
double residentMiB() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
    ADD_FAILURE() << "no VmRSS in /proc/self/status";
    return 0.0;
}

constexpr uint32_t kFrames = 2000, kSettledFrame = 200;
constexpr double kGrowthMiB = 8.0;

class MemoryTest : public test::VulkanTest {};

// `frame(renderer, f)` draws frame f; resident memory after frame kSettledFrame and after the
// last must differ by less than kGrowthMiB.
template <typename DrawFrame> void expectFlat(const Scene& scene, DrawFrame frame) {
    Renderer renderer(test::context(), scene, {16, 16, "final"});
    double settled = 0.0;
    for (uint32_t f = 0; f < kFrames; ++f) {
        frame(renderer, f);
        if (f + 1 == kSettledFrame) settled = residentMiB();
    }
    const double last = residentMiB();
    EXPECT_LT(last - settled, kGrowthMiB)
        << "resident memory " << settled << " MiB after frame " << kSettledFrame << ", " << last
        << " MiB after frame " << kFrames;
}

TEST_F(MemoryTest, TwoThousandStillFramesHoldFlatMemory) {
    const Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    expectFlat(scene, [&](Renderer& r, uint32_t) { r.renderFrame(scene.camera); });
}

// As walkthrough draws them: along the camera path, the cache restarting at its cuts.
TEST_F(MemoryTest, TwoThousandFramesAlongTheCameraPathHoldFlatMemory) {
    const Scene scene = loadScene(test::sourcePath("scenes/cornell-box.json"));
    ASSERT_FALSE(scene.cameraPath.empty());
    const float duration = scene.cameraPath.keys.back().time;
    expectFlat(scene, [&](Renderer& r, uint32_t f) {
        const float t = duration * float(f) / float(kFrames - 1);
        r.setTime(t);
        r.renderFrame(cameraAt(scene.cameraPath, t));
    });
}

} // namespace
