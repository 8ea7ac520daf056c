// Keyboard and mouse as the walkthrough sees them. GLFW's callbacks (attachInput) and a scripted
// input sequence (input_script.h) feed the same InputState, so a script drives exactly the code
// a person's keys and mouse drive; each frame takes a snapshot (InputFrame) and starts afresh.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <string>

struct GLFWwindow;

namespace meadow {

// Key codes are GLFW's (GLFW_KEY_*), 0 .. kKeyCount - 1.
inline constexpr int kKeyCount = 349; // GLFW_KEY_LAST + 1

enum class MouseButton { Left = 0, Right = 1, Middle = 2 };
inline constexpr int kMouseButtonCount = 3;

// What happened during one frame.
struct InputFrame {
    std::array<bool, kKeyCount> down{};    // held at the end of the frame
    std::array<bool, kKeyCount> pressed{}; // went down during the frame (a press and release both count)
    std::array<bool, kMouseButtonCount> mouseDown{};
    std::array<bool, kMouseButtonCount> mousePressed{};
    glm::vec2 mouseDelta{0.0f}; // pixels the cursor moved, x right, y down
    float scroll = 0.0f;        // wheel steps, positive away from the user

    bool held(int key) const { return key >= 0 && key < kKeyCount && down[size_t(key)]; }
    bool tapped(int key) const { return key >= 0 && key < kKeyCount && pressed[size_t(key)]; }
    bool button(MouseButton b) const { return mouseDown[size_t(b)]; }
    bool shift() const;
    bool ctrl() const;
};

class InputState {
  public:
    // GLFW_PRESS / GLFW_RELEASE (GLFW_REPEAT is ignored: held keys are polled per frame).
    void keyEvent(int key, int action);
    void mouseButtonEvent(MouseButton button, bool down);
    // The cursor's absolute position; the first one after attaching only sets the origin.
    void cursorEvent(double x, double y);
    void moveCursor(glm::vec2 delta); // relative motion (scripts)
    void scrollEvent(double steps);
    // Everything up (the window lost focus: keys released elsewhere never arrive).
    void releaseAll();

    // The frame so far; clears what is per frame (presses, motion, scroll).
    InputFrame takeFrame();

    // While set, GLFW's events are dropped (a script drives the walkthrough alone).
    bool ignoreDevices = false;

  private:
    InputFrame current_;
    std::optional<glm::dvec2> cursor_;
};

// Installs GLFW callbacks on `window` that feed `input` (keys, buttons, cursor, wheel, focus).
// Call before anything that chains onto them (the HUD's platform backend does).
void attachInput(GLFWwindow* window, InputState& input);

// Key names used by scripts and help text: "W", "F12", "Escape", "LeftShift", "[", ... (any case).
// Returns -1 for an unknown name.
int keyFromName(const std::string& name);
std::string keyName(int key);
// "left", "right", "middle".
std::optional<MouseButton> mouseButtonFromName(const std::string& name);

} // namespace meadow
