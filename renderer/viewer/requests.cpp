// The viewer's answers to what the person (or the script) asked for: the panel's requests,
// the light dragged over the image, and the report of a scripted run.
#include "viewer/debug_views.h"
#include "viewer/gui.h"
#include "viewer/swapchain.h"
#include "viewer/viewer.h"
#include "viewer/window.h"

#include <GLFW/glfw3.h>

#include <algorithm>

namespace ssgi::viewer {

// Ctrl + left drag over the image moves the light over the floor plane, keeping its height
// (a light under a ceiling stays under it): sideways with the view's right, up the image away
// from the camera; with Shift as well, up the image raises it. A drag across the image moves it
// as far as the camera flies in a second.
void Viewer::dragLight() {
    GLFWwindow* w = window_->handle();
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    auto down = [&](int key) { return glfwGetKey(w, key) == GLFW_PRESS; };
    const bool ctrl = down(GLFW_KEY_LEFT_CONTROL) || down(GLFW_KEY_RIGHT_CONTROL);
    const bool shift = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT);
    const bool held = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool dragging = ctrl && held && !gui_->wantsMouse();
    if (dragging && draggingLight_ && (x != lastCursorX_ || y != lastCursorY_)) {
        const Camera c = fly_.camera();
        glm::vec3 right = c.orientation * glm::vec3(1.0f, 0.0f, 0.0f);
        glm::vec3 forward = c.orientation * glm::vec3(0.0f, 0.0f, -1.0f);
        right.y = forward.y = 0.0f;
        right = glm::length(right) > 1e-4f ? glm::normalize(right) : glm::vec3(1.0f, 0.0f, 0.0f);
        forward = glm::length(forward) > 1e-4f ? glm::normalize(forward) : glm::vec3(0, 0, -1.0f);
        const glm::vec3 away = shift ? glm::vec3(0.0f, 1.0f, 0.0f) : forward;
        const float perPixel = panel_.cameraSpeed / float(std::max(1u, sceneRect().extent.width));
        panel_.light.position +=
            (right * float(x - lastCursorX_) - away * float(y - lastCursorY_)) * perPixel;
        panel_.lightChanged = true;
    }
    draggingLight_ = dragging;
    lastCursorX_ = x;
    lastCursorY_ = y;
}

void Viewer::applyPanelRequests() {
    PanelState& p = panel_;
    if (p.lightChanged) {
        scene_.light = p.light;
        renderer_->setLight(p.light);
        p.lightChanged = false;
    }
    // A view changes what the composite shows (or what the viewer makes of the cache's images)
    // and nothing else: the caches keep converging.
    if (p.viewChanged && !p.settingsChanged) {
        renderer_->setView(viewNames()[size_t(p.view)]);
        p.viewChanged = false;
    }
    if (p.settingsChanged) {
        const Settings previous = scene_.settings;
        scene_.settings = p.settings;
        try {
            rebuildRenderer(Rebuild::Settings);
            p.message.clear();
        } catch (const InputError& e) {
            p.message = e.what();
            scene_.settings = p.settings = previous;
            rebuildRenderer(Rebuild::Settings); // from the old renderer, if it is whole
        }
        p.settingsChanged = p.viewChanged = false;
    }
    if (p.loadScene) {
        p.loadScene = false;
        try {
            loadScene(p.scenePath);
            p.message.clear();
        } catch (const InputError& e) {
            p.message = e.what();
            if (!renderer_) rebuildRenderer();
        }
    }
    if (p.resetCamera) {
        fly_.reset(scene_.camera, p.cameraSpeed);
        p.playPath = false;
        p.resetCamera = false;
    }
    if (p.startRecording) recorder_.start();
    if (p.stopRecording) recorder_.stop();
    p.startRecording = p.stopRecording = false;
    if (p.saveCameraPath) {
        p.saveCameraPath = false;
        try {
            if (recorder_.path().empty()) throw InputError("record a path first");
            writeCameraPath(scene_.sourcePath, p.savePathTo, recorder_.path());
            p.message = std::string("camera path saved to ") + p.savePathTo;
        } catch (const InputError& e) {
            p.message = e.what();
        }
    }
}

void Viewer::recordReport(bool rebuilt) {
    nlohmann::json f;
    f["frame"] = frame_;
    f["window"] = {swapchain_->extent().width, swapchain_->extent().height};
    f["render"] = {renderSize_.width, renderSize_.height};
    const VkRect2D rect = sceneRect();
    f["image_rect"] = {rect.offset.x, rect.offset.y, rect.extent.width, rect.extent.height};
    f["renderer_rebuilt"] = rebuilt;
    const FrameProfile profile = renderer_->lastFrameProfile();
    f["gpu_ms"] = profile.passSumMs();
    f["host_ms"] = profile.hostMs;
    const uint32_t rotations = uint32_t(scene_.settings.cache_rotations);
    for (const std::string& effect : renderer_->cachedEffects()) {
        const CacheSummary s = summariseCache(*renderer_, effect, rotations);
        f["history_max_count"][effect] = s.maxCount;
    }
    report_["per_frame"].push_back(f);
}

} // namespace ssgi::viewer
