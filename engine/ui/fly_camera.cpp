#include "ui/fly_camera.h"

#include <GLFW/glfw3.h>
#include <algorithm>
#include <cmath>

namespace meadow {

void FlyCamera::setPose(const CameraPose& pose) {
    eye = pose.eye;
    glm::vec3 d = glm::normalize(pose.target - pose.eye);
    yaw = std::atan2(d.x, d.z);
    pitch = std::clamp(std::asin(std::clamp(d.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
}

glm::vec3 FlyCamera::forward() const {
    return {std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch)};
}

CameraPose FlyCamera::pose() const {
    return {eye, eye + kLookDistance * forward()};
}

void FlyCamera::update(const InputFrame& in, bool looking, bool keysFree, float dt, const GroundHeight* ground) {
    if (looking) {
        // Dragging right turns right; dragging down looks down.
        yaw -= in.mouseDelta.x * settings.lookRadiansPerPixel;
        pitch = std::clamp(pitch - in.mouseDelta.y * settings.lookRadiansPerPixel, -kMaxPitch, kMaxPitch);
        yaw = std::remainder(yaw, 2.0f * float(M_PI));
    }
    if (in.scroll != 0.0f)
        settings.speed = std::clamp(settings.speed * std::pow(1.25f, in.scroll), kMinFlySpeed, kMaxFlySpeed);
    if (keysFree) {
        float speed = settings.speed;
        if (in.shift())
            speed *= settings.fastFactor;
        if (in.ctrl())
            speed *= settings.slowFactor;
        auto axis = [&](int plus, int minus) { return (in.held(plus) ? 1.0f : 0.0f) - (in.held(minus) ? 1.0f : 0.0f); };
        const float ahead = axis(GLFW_KEY_W, GLFW_KEY_S);
        const float across = axis(GLFW_KEY_D, GLFW_KEY_A);
        // Walking moves on the level whatever the pitch; flying moves along the view.
        const glm::vec3 level(std::sin(yaw), 0.0f, std::cos(yaw));
        // Right = forward x up (y up, right-handed: looking along +z, right is -x).
        const glm::vec3 right = glm::cross(level, glm::vec3(0.0f, 1.0f, 0.0f));
        const glm::vec3 f = walk ? level : forward();
        eye += speed * dt * (ahead * f + across * right);
        if (!walk)
            eye.y += speed * dt * axis(GLFW_KEY_E, GLFW_KEY_Q);
    }
    settle(ground);
}

void FlyCamera::settle(const GroundHeight* ground) {
    if (!ground)
        return;
    std::optional<float> h = ground->at(eye.x, eye.z);
    if (!h)
        return; // beyond the ground: nothing to stand on or stay above
    if (walk)
        eye.y = *h + settings.eyeHeight;
    else
        eye.y = std::max(eye.y, *h + settings.clearance);
}

} // namespace meadow
