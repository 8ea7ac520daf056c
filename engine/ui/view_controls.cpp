#include "ui/view_controls.h"

#include <GLFW/glfw3.h>
#include <algorithm>
#include <cmath>
#include <cstring>

namespace meadow {
namespace {

const KeyBinding kBindings[] = {
    {"W A S D", "move forward, left, back, right"},
    {"Q / E", "down / up (flying)"},
    {"Shift / Ctrl", "hold: 5x faster / 5x slower"},
    {"mouse wheel", "fly speed x1.25 per step"},
    {"right drag, left drag", "look around (left drag off the HUD)"},
    {"G", "walk at eye height on the ground / fly"},
    {"Home", "back to the starting view"},
    {"[ / ]", "wind level down / up by 0.25"},
    {", / .", "time of day back / on by half an hour"},
    {"T", "play / pause the day"},
    {"L", "colour the clumps by level of detail"},
    {"C", "freeze culling (fly away to see what was drawn)"},
    {"P", "play the camera path from its start / stop"},
    {"R", "record a camera path / stop and save it"},
    {"F12", "screenshot to PNG (what the window shows)"},
    {"F1", "hide / show the HUD"},
    {"H", "hide / show this help"},
    {"F11", "fullscreen on / off"},
    {"V", "vsync on / off"},
    {"Esc", "quit"},
};

} // namespace

std::span<const KeyBinding> keyBindings() {
    return kBindings;
}

std::string keyHelpText() {
    size_t width = 0;
    for (const KeyBinding& b : kBindings)
        width = std::max(width, std::strlen(b.keys));
    std::string text;
    for (const KeyBinding& b : kBindings) {
        std::string keys = b.keys;
        keys.resize(width + 2, ' ');
        text += "  " + keys + b.action + "\n";
    }
    return text;
}

ViewRequests applyShortcuts(const InputFrame& in, bool keyboardTaken, ViewControls& c) {
    ViewRequests r;
    r.quit = in.tapped(GLFW_KEY_ESCAPE);
    if (keyboardTaken)
        return r;
    auto toggle = [&](int key, bool& flag) {
        if (in.tapped(key))
            flag = !flag;
    };
    toggle(GLFW_KEY_F1, c.showHud);
    toggle(GLFW_KEY_H, c.showHelp);
    toggle(GLFW_KEY_F11, c.fullscreen);
    toggle(GLFW_KEY_V, c.vsync);
    toggle(GLFW_KEY_L, c.lodColours);
    toggle(GLFW_KEY_C, c.freezeCulling);
    toggle(GLFW_KEY_T, c.playDay);
    r.screenshot = in.tapped(GLFW_KEY_F12);
    r.toggleWalk = in.tapped(GLFW_KEY_G);
    r.resetCamera = in.tapped(GLFW_KEY_HOME);
    r.togglePlayback = in.tapped(GLFW_KEY_P);
    r.toggleRecording = in.tapped(GLFW_KEY_R);
    if (in.tapped(GLFW_KEY_LEFT_BRACKET))
        c.wind.baseLevel = std::max(0.0f, c.wind.baseLevel - kWindStep);
    if (in.tapped(GLFW_KEY_RIGHT_BRACKET))
        c.wind.baseLevel = std::min(c.topWindLevel, c.wind.baseLevel + kWindStep);
    if (in.tapped(GLFW_KEY_COMMA))
        c.hours = std::fmod(c.hours - kHourStep + 24.0, 24.0);
    if (in.tapped(GLFW_KEY_PERIOD))
        c.hours = std::fmod(c.hours + kHourStep, 24.0);
    return r;
}

void advanceDay(ViewControls& c, double seconds) {
    if (c.playDay)
        c.hours = std::fmod(c.hours + double(c.daySpeed) * seconds, 24.0);
}

void applyControls(const ViewControls& c, FrameState& state) {
    state.wind = c.wind;
    state.hours = c.hours;
    state.debugView = c.lodColours ? gpu::kDebugViewLod : gpu::kDebugViewNone;
    state.freezeCulling = c.freezeCulling;
}

} // namespace meadow
