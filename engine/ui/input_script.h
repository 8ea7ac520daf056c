// A scripted input sequence for the walkthrough (`meadow view --script FILE`): what a person
// would do with keys, mouse and window, frame by frame, so that tests (and demos) can drive the
// window without a person. A scripted run steps its clocks by exactly 1/30 s per frame, so the
// camera ends where the script says, whatever the frame rate.
//
// One event per line, "FRAME COMMAND [ARGS]"; '#' starts a comment; frames count rendered frames
// from 0 and must not decrease. Events of frame F happen before frame F is drawn.
//   down KEY | up KEY        hold or release a key (names: W, F12, Escape, LeftShift, [, ...)
//   tap KEY                  down at F, up at F + 1 (one press)
//   mouse-down BUTTON        left, right or middle; mouse-up BUTTON releases it
//   move DX DY               the cursor moves by (DX, DY) pixels during frame F
//   scroll STEPS             the wheel turns (positive: away from the user)
//   resize W H               the window's client area becomes W x H
//   minimize SECONDS         the window is minimised, then restored after SECONDS of wall time
//   log                      print the camera and the controls' state (for tests to check)
//   quit                     end the walkthrough (exit status 0 unless something failed)
#pragma once

#include "ui/input.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace meadow {

struct ScriptEvent {
    enum class Kind { KeyDown, KeyUp, MouseDown, MouseUp, Move, Scroll, Resize, Minimize, Log, Quit };
    uint32_t frame = 0;
    Kind kind = Kind::Log;
    int key = -1;
    MouseButton button = MouseButton::Left;
    glm::vec2 amount{0.0f};         // Move: pixels; Scroll: x steps
    uint32_t width = 0, height = 0; // Resize
    double seconds = 0.0;           // Minimize
    uint32_t line = 0;              // in the source, for messages
};

struct InputScript {
    std::string source;              // file name, for messages
    std::vector<ScriptEvent> events; // sorted by frame, stable
};

// Throws meadow::Error naming `where`, the line and the problem.
InputScript parseInputScript(const std::string& text, const std::string& where);
InputScript loadInputScript(const std::filesystem::path& file);

// Plays a script into an InputState as frames go by.
class ScriptPlayer {
  public:
    explicit ScriptPlayer(InputScript script) : script_(std::move(script)) {}

    // Applies the input events of frames up to `frame` not yet applied to `input`, and returns
    // the others (window, log and quit), in order, for the caller to carry out.
    std::vector<ScriptEvent> advance(uint32_t frame, InputState& input);
    bool finished() const { return next_ >= script_.events.size(); }
    const InputScript& script() const { return script_; }

  private:
    InputScript script_;
    size_t next_ = 0;
};

} // namespace meadow
