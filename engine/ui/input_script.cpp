#include "ui/input_script.h"

#include "core/error.h"

#include <GLFW/glfw3.h>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace meadow {
namespace {

const char* kCommands = "down, up, tap, mouse-down, mouse-up, move, scroll, resize, minimize, log, quit";

struct LineReader {
    std::string where;
    std::vector<std::string> words;
    size_t next = 1; // words[0] is the frame

    [[noreturn]] void fail(const std::string& what) const { throw Error(where + ": " + what); }

    const std::string& word(const char* what) {
        if (next >= words.size())
            fail(words[1] + ": " + what + " is missing");
        return words[next++];
    }
    double number(const char* what, double lo, double hi) {
        const std::string& w = word(what);
        size_t used = 0;
        double v = 0.0;
        try {
            v = std::stod(w, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != w.size() || !std::isfinite(v))
            fail(words[1] + ": " + what + " '" + w + "' is not a number");
        if (v < lo || v > hi) {
            std::ostringstream s;
            s << words[1] << ": " << what << " " << w << " is outside [" << lo << ", " << hi << "]";
            fail(s.str());
        }
        return v;
    }
    int key() {
        const std::string& name = word("a key name");
        int k = keyFromName(name);
        if (k < 0)
            fail("unknown key '" + name +
                 "' (keys: A-Z, 0-9, F1-F12, Space, Escape, Enter, Tab, Shift, Ctrl, Alt, "
                 "Up, Down, Left, Right, PageUp, PageDown, [ ] , . - = / ;)");
        return k;
    }
    MouseButton button() {
        const std::string& name = word("a mouse button");
        auto b = mouseButtonFromName(name);
        if (!b)
            fail("unknown mouse button '" + name + "' (left, right or middle)");
        return *b;
    }
    void end() const {
        if (next < words.size())
            fail(words[1] + ": unexpected '" + words[next] + "'");
    }
};

} // namespace

InputScript parseInputScript(const std::string& text, const std::string& where) {
    InputScript script;
    script.source = where;
    std::istringstream lines(text);
    std::string line;
    uint32_t lineNumber = 0;
    uint32_t lastFrame = 0;
    while (std::getline(lines, line)) {
        ++lineNumber;
        if (size_t hash = line.find('#'); hash != std::string::npos)
            line.erase(hash);
        LineReader r{where + ":" + std::to_string(lineNumber), {}};
        std::istringstream words(line);
        for (std::string w; words >> w;)
            r.words.push_back(w);
        if (r.words.empty())
            continue;
        if (r.words.size() < 2)
            r.fail("expected 'FRAME COMMAND [ARGS]', found only '" + r.words[0] + "'");

        const std::string& frameText = r.words[0];
        if (frameText.empty() || !std::all_of(frameText.begin(), frameText.end(), ::isdigit) || frameText.size() > 9)
            r.fail("the frame '" + frameText + "' is not a whole number (0 to 999999999)");
        ScriptEvent e;
        e.frame = uint32_t(std::stoul(frameText));
        e.line = lineNumber;
        if (e.frame < lastFrame)
            r.fail("frame " + frameText + " comes after frame " + std::to_string(lastFrame) +
                   " (frames must not decrease)");
        lastFrame = e.frame;

        const std::string command = r.word("a command");
        using Kind = ScriptEvent::Kind;
        if (command == "down" || command == "up" || command == "tap") {
            e.kind = command == "up" ? Kind::KeyUp : Kind::KeyDown;
            e.key = r.key();
            r.end();
            script.events.push_back(e);
            if (command == "tap") {
                ScriptEvent release = e;
                release.kind = Kind::KeyUp;
                release.frame = e.frame + 1;
                script.events.push_back(release);
            }
            continue;
        }
        if (command == "mouse-down" || command == "mouse-up") {
            e.kind = command == "mouse-down" ? Kind::MouseDown : Kind::MouseUp;
            e.button = r.button();
        } else if (command == "move") {
            e.kind = Kind::Move;
            e.amount.x = float(r.number("DX", -1e5, 1e5));
            e.amount.y = float(r.number("DY", -1e5, 1e5));
        } else if (command == "scroll") {
            e.kind = Kind::Scroll;
            e.amount.x = float(r.number("STEPS", -100.0, 100.0));
        } else if (command == "resize") {
            e.kind = Kind::Resize;
            e.width = uint32_t(r.number("W", 1, 16384));
            e.height = uint32_t(r.number("H", 1, 16384));
            if (double(e.width) != std::stod(r.words[2]) || double(e.height) != std::stod(r.words[3]))
                r.fail("resize: W and H must be whole numbers of pixels");
        } else if (command == "minimize") {
            e.kind = Kind::Minimize;
            e.seconds = r.number("SECONDS", 0.0, 60.0);
        } else if (command == "log") {
            e.kind = Kind::Log;
        } else if (command == "quit") {
            e.kind = Kind::Quit;
        } else {
            r.fail("unknown command '" + command + "' (commands: " + kCommands + ")");
        }
        r.end();
        script.events.push_back(e);
    }
    // A tap's release lands one frame later than its line; keep the file's order otherwise.
    std::stable_sort(script.events.begin(), script.events.end(),
                     [](const ScriptEvent& a, const ScriptEvent& b) { return a.frame < b.frame; });
    return script;
}

InputScript loadInputScript(const std::filesystem::path& file) {
    const std::string where = "input script " + file.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        throw Error(where + ": no such file");
    std::ifstream in(file);
    if (!in)
        throw Error(where + ": cannot open");
    std::stringstream text;
    text << in.rdbuf();
    InputScript script = parseInputScript(text.str(), where);
    if (script.events.empty())
        throw Error(where + ": the script holds no events");
    return script;
}

std::vector<ScriptEvent> ScriptPlayer::advance(uint32_t frame, InputState& input) {
    std::vector<ScriptEvent> rest;
    using Kind = ScriptEvent::Kind;
    while (next_ < script_.events.size() && script_.events[next_].frame <= frame) {
        const ScriptEvent& e = script_.events[next_++];
        switch (e.kind) {
        case Kind::KeyDown: input.keyEvent(e.key, GLFW_PRESS); break;
        case Kind::KeyUp: input.keyEvent(e.key, GLFW_RELEASE); break;
        case Kind::MouseDown: input.mouseButtonEvent(e.button, true); break;
        case Kind::MouseUp: input.mouseButtonEvent(e.button, false); break;
        case Kind::Move: input.moveCursor(e.amount); break;
        case Kind::Scroll: input.scrollEvent(e.amount.x); break;
        default: rest.push_back(e); break;
        }
    }
    return rest;
}

} // namespace meadow
