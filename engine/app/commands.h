// The meadow subcommands (DESIGN.md section 4). Each takes its arguments after the command
// name and returns the process exit status; errors are thrown as meadow::Error.
#pragma once

#include <string>
#include <vector>

namespace meadow {

using Args = std::vector<std::string>;

int runPrecompute(const Args& args);
int runInspect(const Args& args);
int runRender(const Args& args);
int runBench(const Args& args);
int runView(const Args& args);
int runSheet(const Args& args);
int runSheet(const Args& args);

// True when `args` asks for help; prints `text` then.
bool printHelpIfAsked(const Args& args, const char* text);

} // namespace meadow
