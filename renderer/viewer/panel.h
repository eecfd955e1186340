// The ImGui panel: what the viewer shows (device, sizes, per-pass GPU timings with a history
// graph) and what it lets one change live (every method setting of the scene, the light, the
// view, the camera path, the scene file). The panel only edits this state and raises requests;
// the viewer acts on them after the frame.
#pragma once

#include "graph/frame_graph.h"
#include "scene/scene.h"

#include <deque>
#include <map>
#include <string>
#include <vector>

namespace ssgi::viewer {

// The last frames' profiles, for the graphs and for the same statistics `render --profile`
// prints (median, min, max per pass; the passes added up beside the host clock).
struct TimingHistory {
    static constexpr size_t kFrames = 120;
    std::vector<std::string> order; // passes in frame order
    std::map<std::string, std::deque<float>> perPass;
    std::deque<float> total, host;
    ProfileLog recent{0}; // the last kFrames frames, none left out
    void add(const FrameProfile& frame);
    void clear();
};

struct PanelState {
    // Shown.
    std::string sceneFile, device, message;
    VkExtent2D windowSize{}, renderSize{};
    float secondsPerFrame = 0.0f;
    uint32_t frame = 0;
    TimingHistory history;
    std::vector<std::string> cachedEffects;
    bool cacheAvailable = false;

    // Edited live.
    Settings settings; // the scene's, as edited
    SpotLight light;
    int view = 0;       // index into viewNames()
    int cacheView = -1; // index into cacheViews(), -1: the composite's view
    int cacheEffect = 0;
    bool playPath = false;
    float pathTime = 0.0f, pathLength = 0.0f;
    float cameraSpeed = 1.0f;
    bool recording = false;
    size_t recordedKeys = 0;
    char scenePath[1024] = {};
    char savePathTo[1024] = {};

    // Raised by the panel, cleared by the viewer.
    bool settingsChanged = false, lightChanged = false, viewChanged = false;
    bool loadScene = false, saveCameraPath = false, screenshot = false;
    bool startRecording = false, stopRecording = false, resetCamera = false;
};

// Draws the panel as a window of `width` pixels along the left edge, `height` tall.
void drawPanel(PanelState& state, float width, float height);

} // namespace ssgi::viewer
