// The fly camera: W/A/S/D move along the view and sideways, Q/E down and up, Shift four times
// faster; dragging with the right mouse button turns the view (yaw about world up, pitch).
#pragma once

#include "scene/scene.h"

struct GLFWwindow;

namespace ssgi::viewer {

class FlyCamera {
public:
    // Starts where `camera` is; `speed` in scene units per second.
    void reset(const Camera& camera, float speed);
    // Moves by the keys held and the mouse dragged since the last call, `seconds` after it.
    // Input ImGui takes (a focused text field, a drag on the panel) is left to ImGui.
    // Returns whether the camera moved.
    bool update(GLFWwindow* window, float seconds, bool keyboardFree, bool mouseFree);
    Camera camera() const;
    float speed = 1.0f;

private:
    glm::vec3 position_{0.0f};
    float yaw_ = 0.0f, pitch_ = 0.0f; // radians; yaw 0 looks along -Z
    float yfov_ = 0.7f, znear_ = 0.01f, zfar_ = 100.0f;
    double lastX_ = 0.0, lastY_ = 0.0;
    bool dragging_ = false;
};

} // namespace ssgi::viewer
