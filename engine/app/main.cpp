// meadow: renders vast, living plant fields. main() parses the command and dispatches; every
// error surfaces here as one message on stderr and a non-zero exit status.
#include "app/commands.h"
#include "core/error.h"

#include <cstdio>
#include <cstring>
#include <exception>

namespace {

const char* kUsage = R"(usage: meadow <command> [arguments]

commands:
  precompute SCENE   build a scene's library (cached)
  inspect LIB        facts about a library, as JSON
  render SCENE       offscreen frames to PNG or EXR
  view SCENE         the interactive walkthrough window
  bench SCENE        timings as JSON
  sheet SCENE        an image sheet of one clump's motion at every wind level

Scenes live in data/scenes (the default is data/scenes/irises.json).
`meadow <command> --help` tells more.
)";

} // namespace

int main(int argc, char** argv) {
    using namespace meadow;
    if (argc < 2) {
        std::fputs(kUsage, stderr);
        return 2;
    }
    std::string command = argv[1];
    Args args(argv + 2, argv + argc);
    if (command == "--help" || command == "-h" || command == "help") {
        std::fputs(kUsage, stdout);
        return 0;
    }
    try {
        if (command == "precompute")
            return runPrecompute(args);
        if (command == "inspect")
            return runInspect(args);
        if (command == "render")
            return runRender(args);
        if (command == "bench")
            return runBench(args);
        if (command == "view")
            return runView(args);
        if (command == "sheet")
            return runSheet(args);
        std::fprintf(stderr,
                     "meadow: unknown command '%s' (commands: precompute, inspect, render, view, bench, sheet)\n",
                     command.c_str());
        return 2;
    } catch (const Error& e) {
        std::fprintf(stderr, "meadow: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "meadow: internal error: %s\n", e.what());
        return 1;
    }
}
