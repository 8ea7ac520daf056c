#include "ui/input.h"

#include <GLFW/glfw3.h>
#include <algorithm>
#include <cctype>
#include <utility>
#include <vector>

namespace meadow {
namespace {

static_assert(kKeyCount == GLFW_KEY_LAST + 1);

const std::vector<std::pair<std::string, int>>& namedKeys() {
    static const std::vector<std::pair<std::string, int>> keys = [] {
        std::vector<std::pair<std::string, int>> k = {
            {"Space", GLFW_KEY_SPACE},
            {"Escape", GLFW_KEY_ESCAPE},
            {"Esc", GLFW_KEY_ESCAPE},
            {"Enter", GLFW_KEY_ENTER},
            {"Tab", GLFW_KEY_TAB},
            {"Backspace", GLFW_KEY_BACKSPACE},
            {"Up", GLFW_KEY_UP},
            {"Down", GLFW_KEY_DOWN},
            {"Left", GLFW_KEY_LEFT},
            {"Right", GLFW_KEY_RIGHT},
            {"PageUp", GLFW_KEY_PAGE_UP},
            {"PageDown", GLFW_KEY_PAGE_DOWN},
            {"Home", GLFW_KEY_HOME},
            {"End", GLFW_KEY_END},
            {"Shift", GLFW_KEY_LEFT_SHIFT},
            {"LeftShift", GLFW_KEY_LEFT_SHIFT},
            {"RightShift", GLFW_KEY_RIGHT_SHIFT},
            {"Ctrl", GLFW_KEY_LEFT_CONTROL},
            {"LeftCtrl", GLFW_KEY_LEFT_CONTROL},
            {"RightCtrl", GLFW_KEY_RIGHT_CONTROL},
            {"Alt", GLFW_KEY_LEFT_ALT},
            {"[", GLFW_KEY_LEFT_BRACKET},
            {"]", GLFW_KEY_RIGHT_BRACKET},
            {",", GLFW_KEY_COMMA},
            {".", GLFW_KEY_PERIOD},
            {"-", GLFW_KEY_MINUS},
            {"=", GLFW_KEY_EQUAL},
            {"/", GLFW_KEY_SLASH},
            {";", GLFW_KEY_SEMICOLON},
        };
        for (char c = 'A'; c <= 'Z'; ++c)
            k.push_back({std::string(1, c), GLFW_KEY_A + (c - 'A')});
        for (char c = '0'; c <= '9'; ++c)
            k.push_back({std::string(1, c), GLFW_KEY_0 + (c - '0')});
        for (int f = 1; f <= 12; ++f)
            k.push_back({"F" + std::to_string(f), GLFW_KEY_F1 + f - 1});
        return k;
    }();
    return keys;
}

std::string lower(std::string s) {
    for (char& c : s)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

InputState& inputOf(GLFWwindow* window) {
    return *static_cast<InputState*>(glfwGetWindowUserPointer(window));
}

void onKey(GLFWwindow* window, int key, int, int action, int) {
    InputState& input = inputOf(window);
    if (!input.ignoreDevices)
        input.keyEvent(key, action);
}

void onMouseButton(GLFWwindow* window, int button, int action, int) {
    InputState& input = inputOf(window);
    if (!input.ignoreDevices && button >= 0 && button < kMouseButtonCount)
        input.mouseButtonEvent(MouseButton(button), action == GLFW_PRESS);
}

void onCursor(GLFWwindow* window, double x, double y) {
    InputState& input = inputOf(window);
    if (!input.ignoreDevices)
        input.cursorEvent(x, y);
}

void onScroll(GLFWwindow* window, double, double y) {
    InputState& input = inputOf(window);
    if (!input.ignoreDevices)
        input.scrollEvent(y);
}

void onFocus(GLFWwindow* window, int focused) {
    InputState& input = inputOf(window);
    if (!input.ignoreDevices && !focused)
        input.releaseAll();
}

} // namespace

bool InputFrame::shift() const {
    return held(GLFW_KEY_LEFT_SHIFT) || held(GLFW_KEY_RIGHT_SHIFT);
}

bool InputFrame::ctrl() const {
    return held(GLFW_KEY_LEFT_CONTROL) || held(GLFW_KEY_RIGHT_CONTROL);
}

void InputState::keyEvent(int key, int action) {
    if (key < 0 || key >= kKeyCount)
        return; // GLFW_KEY_UNKNOWN
    if (action == GLFW_PRESS) {
        current_.down[size_t(key)] = true;
        current_.pressed[size_t(key)] = true;
    } else if (action == GLFW_RELEASE) {
        current_.down[size_t(key)] = false;
    }
}

void InputState::mouseButtonEvent(MouseButton button, bool down) {
    current_.mouseDown[size_t(button)] = down;
    if (down)
        current_.mousePressed[size_t(button)] = true;
}

void InputState::cursorEvent(double x, double y) {
    if (cursor_)
        current_.mouseDelta += glm::vec2(float(x - cursor_->x), float(y - cursor_->y));
    cursor_ = glm::dvec2(x, y);
}

void InputState::moveCursor(glm::vec2 delta) {
    current_.mouseDelta += delta;
}

void InputState::scrollEvent(double steps) {
    current_.scroll += float(steps);
}

void InputState::releaseAll() {
    current_.down.fill(false);
    current_.mouseDown.fill(false);
}

InputFrame InputState::takeFrame() {
    InputFrame frame = current_;
    current_.pressed.fill(false);
    current_.mousePressed.fill(false);
    current_.mouseDelta = glm::vec2(0.0f);
    current_.scroll = 0.0f;
    return frame;
}

void attachInput(GLFWwindow* window, InputState& input) {
    glfwSetWindowUserPointer(window, &input);
    glfwSetKeyCallback(window, onKey);
    glfwSetMouseButtonCallback(window, onMouseButton);
    glfwSetCursorPosCallback(window, onCursor);
    glfwSetScrollCallback(window, onScroll);
    glfwSetWindowFocusCallback(window, onFocus);
}

int keyFromName(const std::string& name) {
    const std::string wanted = lower(name);
    for (const auto& [keyNameText, key] : namedKeys())
        if (lower(keyNameText) == wanted)
            return key;
    return -1;
}

std::string keyName(int key) {
    for (const auto& [name, code] : namedKeys())
        if (code == key)
            return name;
    return "key " + std::to_string(key);
}

std::optional<MouseButton> mouseButtonFromName(const std::string& name) {
    const std::string n = lower(name);
    if (n == "left")
        return MouseButton::Left;
    if (n == "right")
        return MouseButton::Right;
    if (n == "middle")
        return MouseButton::Middle;
    return std::nullopt;
}

} // namespace meadow
