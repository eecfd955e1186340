// The viewer: a window around the same Renderer the headless programs use. Each frame it moves
// the camera (fly camera or the scene's path), renders the frame with the renderer, and
// presents it with the panel over it. Changing a setting or the window's size builds the
// renderer again (its caches restart: no history carries across sizes or settings); changing
// the view does not.
#pragma once

#include "app/cli.h"
#include "renderer.h"
#include "viewer/camera_path_io.h"
#include "viewer/fly_camera.h"
#include "viewer/panel.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <string>

namespace ssgi::viewer {

class Window;
class Swapchain;
class Gui;
class Presenter;

struct ViewerOptions {
    cli::CommonArgs common; // the scene; --size is the window's size
    // Scripted runs (tests, figures): stop after `frames` frames (0: run until closed).
    uint32_t frames = 0;
    bool playPath = false;
    float pathStep = 0.0f;          // path seconds per frame; 0: real time, or the whole path
                                    // over `frames` in a scripted run
    uint32_t resizeAt = UINT32_MAX; // frame at which the window is resized to `resizeTo`
    VkExtent2D resizeTo{};
    std::string view = "final";
    std::string cacheView; // a cache view by name (e.g. "converged mask")
    std::string cacheEffect = "ao";
    std::string screenshot; // PNG of the whole window after the last frame
    std::string report;     // JSON: per frame sizes, timings, history counts; validation
    std::string recordInto; // record the camera and write the scene with that path here
    float renderScale = 1.0f;
    uint32_t panelWidth = 340;
};

class Viewer {
public:
    explicit Viewer(const ViewerOptions& options);
    ~Viewer();
    // Runs until the window closes or the scripted frames are done; the exit status.
    int run();

private:
    void loadScene(const std::string& path);
    // Anew: the scene loaded; Resized: the window's size changed (the caches resampled);
    // Settings: the panel's settings changed (the renderer made from the old one's parts: its
    // pipelines, the scene on the device and what it drew once stay where the change allows).
    enum class Rebuild { Anew, Resized, Settings };
    void rebuildRenderer(Rebuild why = Rebuild::Anew);
    VkRect2D sceneRect() const;
    Camera nextCamera(float seconds);
    void dragLight();
    void applyPanelRequests();
    void drawFrame(bool screenshot);
    void recordReport(bool rebuilt);

    ViewerOptions options_;
    std::unique_ptr<Window> window_;
    std::unique_ptr<vk::Context> ctx_;
    std::unique_ptr<Swapchain> swapchain_;
    std::unique_ptr<Gui> gui_;
    std::unique_ptr<Presenter> presenter_;
    Scene scene_;
    std::unique_ptr<Renderer> renderer_;
    VkExtent2D renderSize_{};
    FlyCamera fly_;
    PathRecorder recorder_;
    PanelState panel_;
    bool showPanel_ = true;
    bool f12Down_ = false, tabDown_ = false;
    double lastCursorX_ = 0.0, lastCursorY_ = 0.0;
    bool draggingLight_ = false;
    float shownPathTime_ = 0.0f; // the path time the camera was last put at
    uint32_t frame_ = 0;
    bool rebuiltThisFrame_ = false;
    nlohmann::json report_;
};

} // namespace ssgi::viewer
