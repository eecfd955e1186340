// The desktop viewer as a person would see it, without a person: it runs under Xvfb on
// the default Vulkan device (lavapipe without a GPU) with the validation layer on, plays the
// Cornell box's camera path, is resized in the middle, and writes a screenshot of its window.
// The screenshot must show the scene (the red and green walls, close to a headless render of the
// same camera) and the panel (ImGui's title bar and text); the resize must restart every history
// and leave the validation layer silent.
#include "image_io.h"
#include "renderer.h"
#include "scene/camera.h"
#include "support.h"

#include <nlohmann/json.hpp>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace ssgi;

namespace {

// An X server of our own on a display it picks itself (-displayfd), so tests running at the same
// time never race for one; stopped with the test.
class Xvfb {
public:
    Xvfb() {
        int fds[2];
        if (pipe(fds) != 0) return;
        pid_ = fork();
        if (pid_ == 0) {
            close(fds[0]);
            freopen("/dev/null", "w", stderr);
            const std::string fd = std::to_string(fds[1]);
            execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x800x24",
                   "-nolisten", "tcp", static_cast<char*>(nullptr));
            _exit(127);
        }
        close(fds[1]);
        std::string number;
        char c;
        while (read(fds[0], &c, 1) == 1 && c != '\n')
            number += c;
        close(fds[0]);
        if (!number.empty()) display_ = ":" + number;
    }
    ~Xvfb() {
        if (pid_ > 0) {
            kill(pid_, SIGTERM);
            waitpid(pid_, nullptr, 0);
        }
    }
    const std::string& display() const { return display_; }

private:
    pid_t pid_ = -1;
    std::string display_;
};

bool hasXvfb() {
    return std::system("command -v Xvfb >/dev/null 2>&1") == 0;
}

using Result = test::CommandResult;

Result runViewer(const std::string& environment, const std::string& arguments) {
#ifdef SSGI_VIEWER_BINARY
    return test::runCommand(environment + " " + SSGI_VIEWER_BINARY + " " + arguments);
#else
    return test::runCommand("false");
#endif
}

struct Image {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
    glm::vec3 at(uint32_t x, uint32_t y) const {
        const size_t i = 4 * (size_t(y) * width + x);
        return {rgba[i], rgba[i + 1], rgba[i + 2]};
    }
};

class Viewer : public ::testing::Test {
protected:
    void SetUp() override {
#ifndef SSGI_VIEWER_BINARY
        GTEST_SKIP() << "the viewer is not built (needs libglfw3-dev and libimgui-dev)";
#endif
        dir = fs::temp_directory_path() /
              ("ssgi-viewer-" + std::to_string(getpid()) + "-" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override {
        fs::remove_all(dir);
    }
    std::string path(const std::string& name) const {
        return (dir / name).string();
    }
    fs::path dir;
};

// ImGui's dark style: the active title bar (0.16, 0.29, 0.48).
bool titleBarColour(glm::vec3 c) {
    return glm::length(c - glm::vec3(0.16f, 0.29f, 0.48f)) < 0.04f;
}
bool redWall(glm::vec3 c) {
    return c.r > 0.25f && c.r > 2.5f * c.g && c.r > 2.5f * c.b;
}
bool greenWall(glm::vec3 c) {
    return c.g > 0.2f && c.g > 1.5f * c.r && c.g > 1.5f * c.b;
}

constexpr uint32_t kFrames = 10, kResizeAt = 5;
// Along the path the histories count every frame they accumulate; the blur budgets, which cut a
// moving history's weight (and count) once it has blurred enough, are lifted here so that the
// count shows the restarts alone (the budgets have their own tests in test_cache_motion).
constexpr const char* kNoBlurBudget =
    " --set cache_blur_shadow=1e6 --set cache_blur_ao=1e6 --set cache_blur_indirect=1e6";
// The screen-space bounce (indirect_method 1), whose history's count is read along the path.
constexpr const char* kBounce = " --set indirect_method=1";

TEST_F(Viewer, ScriptedPathWithResizeShowsSceneAndPanel) {
    if (!hasXvfb()) GTEST_SKIP() << "Xvfb is not installed (tools/setup.sh installs it)";
    Xvfb x;
    ASSERT_FALSE(x.display().empty()) << "Xvfb did not start";
    const std::string scenePath = test::sourcePath("scenes/cornell-box.json");
    const Result r = runViewer(
        "DISPLAY=" + x.display(),
        scenePath + " --validation --size 640x400 --frames " + std::to_string(kFrames) +
            " --play-path --resize-at " + std::to_string(kResizeAt) + " 720x440 --set " +
            "indirect_vpls=128" + kBounce + kNoBlurBudget + " --screenshot " + path("viewer.png") +
            " --report " + path("report.json") + " --record-into " + path("recorded.json"));
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("validation"), std::string::npos) << r.output;

    // The report: every frame rendered, the resize seen, every history carried over as half a
    // sample.
    nlohmann::json report = nlohmann::json::parse(std::ifstream(path("report.json")));
    EXPECT_EQ(report["validation"], true);
    EXPECT_EQ(report["validation_messages"], 0);
    ASSERT_EQ(report["frames"], kFrames);
    const auto& frames = report["per_frame"];
    const uint32_t panel = report["panel_width"];
    uint32_t resizedAt = 0;
    for (uint32_t f = 0; f < kFrames; ++f)
        if (frames[f]["window"][0] == 720 && resizedAt == 0) resizedAt = f;
    ASSERT_GE(resizedAt, kResizeAt) << "the window was resized before it was asked to be";
    ASSERT_LE(resizedAt, kResizeAt + 1) << "the resize was not seen";
    for (uint32_t f = 0; f < kFrames; ++f) {
        const auto& frame = frames[f];
        const bool after = f >= resizedAt;
        EXPECT_EQ(frame["window"][0], after ? 720 : 640) << "frame " << f;
        EXPECT_EQ(frame["render"][0], frame["image_rect"][2]) << "frame " << f;
        EXPECT_EQ(frame["image_rect"][0].get<uint32_t>() + frame["render"][0].get<uint32_t>(),
                  after ? 720u : 640u)
            << "frame " << f;
        EXPECT_EQ(frame["render"][1], after ? 440 : 400) << "frame " << f;
        EXPECT_EQ(frame["renderer_rebuilt"], f == 0 || f == resizedAt) << "frame " << f;
        // A history counts the frames it has accumulated: from 1 on the first frame; at the new
        // size its resampled history counts as half a sample (Renderer::continueFrom), so from
        // 1.5.
        const float expected = after ? float(f - resizedAt) + 1.5f : float(f + 1);
        for (const char* effect : {"shadow", "ao", "indirect"})
            EXPECT_EQ(frame["history_max_count"][effect].get<float>(), expected)
                << effect << ", frame " << f;
    }

    // The screenshot: the whole window, the panel on the left, the scene beside it.
    Image shot;
    shot.rgba = readImage(path("viewer.png"), shot.width, shot.height);
    ASSERT_EQ(shot.width, 720u);
    ASSERT_EQ(shot.height, 440u);
    size_t title = 0, titleArea = 0, text = 0, panelArea = 0;
    for (uint32_t y = 0; y < shot.height; ++y)
        for (uint32_t x = 0; x < panel; ++x) {
            const glm::vec3 c = shot.at(x, y);
            if (y >= 2 && y < 16) {
                ++titleArea;
                title += titleBarColour(c);
            } else if (y >= 20) {
                ++panelArea;
                text += c.r > 0.8f && c.g > 0.8f && c.b > 0.8f;
            }
        }
    const double titleFraction = double(title) / double(titleArea);
    const double textFraction = double(text) / double(panelArea);
    EXPECT_GT(titleFraction, 0.6) << "no ImGui title bar where the panel should be";
    EXPECT_GT(textFraction, 0.005) << "no text in the panel";
    EXPECT_LT(textFraction, 0.2) << "the panel is not ImGui's dark window";

    size_t red = 0, green = 0;
    const uint32_t sceneWidth = shot.width - panel;
    for (uint32_t y = 0; y < shot.height; ++y)
        for (uint32_t x = panel; x < shot.width; ++x) {
            red += redWall(shot.at(x, y));
            green += greenWall(shot.at(x, y));
        }
    const double sceneArea = double(sceneWidth) * shot.height;
    EXPECT_GT(red / sceneArea, 0.05) << "no red wall in the scene's part of the window";
    EXPECT_GT(green / sceneArea, 0.05) << "no green wall in the scene's part of the window";

    // The same camera (the path's end) rendered headless: the scene's part of the window is
    // that image, up to the noise of different histories.
    Scene scene = loadScene(scenePath);
    scene.settings.indirect_vpls = 128;
    scene.settings.indirect_method = 1;
    const uint32_t accumulated = kFrames - resizedAt;
    Renderer renderer(test::context(), scene, {sceneWidth, shot.height, "final"});
    const Camera camera = cameraAt(scene.cameraPath, scene.cameraPath.keys.back().time);
    for (uint32_t f = 0; f < accumulated; ++f)
        renderer.renderFrame(camera);
    auto differenceFrom = [&](const std::vector<float>& headless) {
        double sum = 0.0;
        for (uint32_t y = 0; y < shot.height; ++y)
            for (uint32_t x = 0; x < sceneWidth; ++x) {
                const size_t i = 4 * (size_t(y) * sceneWidth + x);
                const glm::vec3 h(headless[i], headless[i + 1], headless[i + 2]);
                const glm::vec3 d = glm::abs(shot.at(panel + x, y) - h);
                sum += (d.r + d.g + d.b) / 3.0;
            }
        return sum / sceneArea;
    };
    const double difference = differenceFrom(renderer.readImage("ldr"));
    // The same measure against another camera of the path (its second key): what a wrong image
    // would score.
    Renderer other(test::context(), scene, {sceneWidth, shot.height, "final"});
    other.renderFrame(cameraAt(scene.cameraPath, scene.cameraPath.keys[1].time));
    const double otherCamera = differenceFrom(other.readImage("ldr"));
    std::printf("viewer screenshot: title bar %.3f, panel text %.4f, red %.3f, green %.3f, "
                "mean |window - headless| %.4f (another camera: %.4f)\n",
                titleFraction, textFraction, red / sceneArea, green / sceneArea, difference,
                otherCamera);
    EXPECT_LT(difference, 0.05);
    EXPECT_LT(difference, 0.5 * otherCamera);

    // The recorded path went back into a scene file that loads, one key a frame, along the
    // scene's own path.
    const Scene recorded = loadScene(path("recorded.json"));
    ASSERT_EQ(recorded.cameraPath.keys.size(), kFrames);
    EXPECT_EQ(recorded.instances.size(), scene.instances.size());
    const float length = scene.cameraPath.keys.back().time;
    for (uint32_t f = 0; f < kFrames; ++f) {
        const float t = length * float(f) / float(kFrames - 1);
        EXPECT_NEAR(recorded.cameraPath.keys[f].time, t, 1e-3f);
        const glm::vec3 expected = cameraAt(scene.cameraPath, t).position;
        EXPECT_LT(glm::length(recorded.cameraPath.keys[f].camera.position - expected), 1e-3f);
    }
}

// The cache's own views (made from the histories on the CPU) draw, validation-clean: on the
// first frame no pixel has a history, so the disocclusion mask covers all the geometry.
TEST_F(Viewer, DisocclusionViewOnTheFirstFrame) {
    if (!hasXvfb()) GTEST_SKIP() << "Xvfb is not installed (tools/setup.sh installs it)";
    Xvfb x;
    ASSERT_FALSE(x.display().empty()) << "Xvfb did not start";
    const Result r = runViewer("DISPLAY=" + x.display(),
                               test::sourcePath("scenes/cornell-box.json") +
                                   " --validation --size 560x300 --frames 1 --set indirect=0 "
                                   "--cache-view disocclusion --effect ao --report " +
                                   path("report.json") + " --screenshot " + path("mask.png"));
    ASSERT_EQ(r.status, 0) << r.output;
    const uint32_t panel = nlohmann::json::parse(std::ifstream(path("report.json")))["panel_width"];
    Image shot;
    shot.rgba = readImage(path("mask.png"), shot.width, shot.height);
    size_t red = 0;
    for (uint32_t y = 0; y < shot.height; ++y)
        for (uint32_t x = panel; x < shot.width; ++x) {
            const glm::vec3 c = shot.at(x, y);
            red += c.r > 0.85f && c.g < 0.15f && c.b < 0.15f;
        }
    const double fraction = double(red) / (double(shot.width - panel) * shot.height);
    std::printf("disocclusion mask on the first frame: %.3f of the image\n", fraction);
    EXPECT_GT(fraction, 0.9);
}

// Bad input: a clear message and a non-zero status, before any window is needed.
TEST_F(Viewer, BadInput) {
    Result r = runViewer("", path("missing.json") + " --frames 1");
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("error:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("missing.json"), std::string::npos) << r.output;

    r = runViewer("", "--frames 1 --view nonsense");
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("nonsense"), std::string::npos) << r.output;

    r = runViewer("env -u DISPLAY -u WAYLAND_DISPLAY", "--frames 1");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("cannot open a window"), std::string::npos) << r.output;
}

} // namespace
