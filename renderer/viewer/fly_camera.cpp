#include "viewer/fly_camera.h"

#include "scene/camera.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

namespace ssgi::viewer {

namespace {

glm::vec3 direction(float yaw, float pitch) {
    return {std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
}

constexpr float kPitchLimit = 1.55f; // just short of straight up or down
constexpr float kRadiansPerPixel = 0.004f;

} // namespace

void FlyCamera::reset(const Camera& camera, float newSpeed) {
    position_ = camera.position;
    const glm::vec3 d = camera.orientation * glm::vec3(0.0f, 0.0f, -1.0f);
    yaw_ = std::atan2(d.x, -d.z);
    pitch_ = std::asin(std::clamp(d.y, -1.0f, 1.0f));
    yfov_ = camera.yfov;
    znear_ = camera.znear;
    zfar_ = camera.zfar;
    speed = newSpeed;
}

Camera FlyCamera::camera() const {
    Camera c;
    c.position = position_;
    c.orientation = lookRotation(direction(yaw_, pitch_), glm::vec3(0.0f, 1.0f, 0.0f));
    c.yfov = yfov_;
    c.znear = znear_;
    c.zfar = zfar_;
    return c;
}

bool FlyCamera::update(GLFWwindow* window, float seconds, bool keyboardFree, bool mouseFree) {
    bool moved = false;
    double x, y;
    glfwGetCursorPos(window, &x, &y);
    const bool held = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (held && (dragging_ || mouseFree)) {
        if (dragging_ && (x != lastX_ || y != lastY_)) {
            yaw_ += float(x - lastX_) * kRadiansPerPixel;
            pitch_ = std::clamp(pitch_ - float(y - lastY_) * kRadiansPerPixel, -kPitchLimit,
                                kPitchLimit);
            moved = true;
        }
        dragging_ = true;
    } else {
        dragging_ = false;
    }
    lastX_ = x;
    lastY_ = y;
    if (!keyboardFree) return moved;

    auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
    const glm::vec3 forward = direction(yaw_, pitch_);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    glm::vec3 step(0.0f);
    if (down(GLFW_KEY_W)) step += forward;
    if (down(GLFW_KEY_S)) step -= forward;
    if (down(GLFW_KEY_D)) step += right;
    if (down(GLFW_KEY_A)) step -= right;
    if (down(GLFW_KEY_E)) step.y += 1.0f;
    if (down(GLFW_KEY_Q)) step.y -= 1.0f;
    if (step != glm::vec3(0.0f)) {
        const float boost = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT) ? 4.0f : 1.0f;
        position_ += glm::normalize(step) * speed * boost * seconds;
        moved = true;
    }
    return moved;
}

} // namespace ssgi::viewer
