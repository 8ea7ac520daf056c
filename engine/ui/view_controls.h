// What a person steers in the walkthrough besides the camera: the wind, the time of day, debug
// views and the window; the keyboard shortcuts for them and the help text that lists every key
// (shown on screen and by `meadow view --help`, from the one table).
#pragma once

#include "render/field_renderer.h"
#include "ui/input.h"

#include <span>
#include <string>

namespace meadow {

struct ViewControls {
    WindState wind;
    float topWindLevel = 3.0f; // the scene's strongest wind level
    double hours = 12.0;       // time of day
    bool playDay = false;
    float daySpeed = 0.5f; // hours of the day per second while it plays
    bool lodColours = false;
    bool freezeCulling = false;
    bool vsync = true;
    bool fullscreen = false;
    bool showHud = true;
    bool showHelp = false;
};

// One-shot requests from keys or HUD buttons; the walkthrough carries them out this frame.
struct ViewRequests {
    bool quit = false;
    bool screenshot = false;
    bool toggleWalk = false;
    bool resetCamera = false;
    bool togglePlayback = false;
    bool toggleRecording = false;
};

struct KeyBinding {
    const char* keys;
    const char* action;
};
std::span<const KeyBinding> keyBindings();
// The table as indented text lines, for --help.
std::string keyHelpText();

// Steps per key press.
inline constexpr float kWindStep = 0.25f; // levels
inline constexpr double kHourStep = 0.5;  // hours

// Carries out the shortcut keys pressed this frame on `controls`; returns the requests. Keys are
// ignored while `keyboardTaken` (a HUD text field has the keyboard), except Escape.
ViewRequests applyShortcuts(const InputFrame& input, bool keyboardTaken, ViewControls& controls);

// Plays the day forward by `seconds` of walkthrough time when playDay is on (wraps at 24 h).
void advanceDay(ViewControls& controls, double seconds);

// The renderer's per-frame state for these controls (wind, time of day, debug view, freeze).
void applyControls(const ViewControls& controls, FrameState& state);

} // namespace meadow
