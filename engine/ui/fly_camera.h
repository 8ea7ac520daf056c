// The walkthrough's camera: free flight (mouse look, W A S D along the view, Q / E down and up)
// or walking (W A S D on the level, the eye at a person's height above the ground as drawn).
// Pure CPU state stepped by an InputFrame, so tests can fly it without a window.
#pragma once

#include "render/camera_path.h"
#include "ui/ground_height.h"
#include "ui/input.h"

namespace meadow {

struct FlySettings {
    float speed = 5.0f;                 // m/s; the mouse wheel scales it by 1.25 per step
    float fastFactor = 5.0f;            // while Shift is held
    float slowFactor = 0.2f;            // while Ctrl is held
    float lookRadiansPerPixel = 0.003f; // mouse look
    float eyeHeight = 1.7f;             // walk mode: the eye above the ground
    float clearance = 0.3f;             // flight: never closer to the ground than this
};

inline constexpr float kMinFlySpeed = 0.25f, kMaxFlySpeed = 200.0f;
// How far ahead of the eye pose() puts the target: far enough that a path splined through
// recorded targets turns smoothly.
inline constexpr float kLookDistance = 10.0f;
// The pitch stays this far from straight up or down (lookAt's up is +y).
inline constexpr float kMaxPitch = 1.5f;

class FlyCamera {
  public:
    explicit FlyCamera(const CameraPose& pose) { setPose(pose); }

    void setPose(const CameraPose& pose);
    CameraPose pose() const;
    glm::vec3 forward() const;

    // One frame of `dt` seconds: turns by the mouse motion when `looking`, scales the speed by
    // the wheel, and when `keysFree` moves by the held keys. `ground` (may be null) keeps the eye
    // above the ground, or at eyeHeight above it while walking.
    void update(const InputFrame& input, bool looking, bool keysFree, float dt, const GroundHeight* ground);
    // Puts the eye where walk mode wants it (call after switching walk on).
    void settle(const GroundHeight* ground);

    glm::vec3 eye{0.0f};
    float yaw = 0.0f;   // radians around +y; 0 looks along +z, pi/2 along +x
    float pitch = 0.0f; // radians, positive looks up
    bool walk = false;
    FlySettings settings;
};

} // namespace meadow
