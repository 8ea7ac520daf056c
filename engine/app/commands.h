// The meadow subcommands (docs/INTERFACE.md). Each takes its arguments after the command
// name and returns the process exit status; errors are thrown as meadow::Error.
#pragma once

#include <functional>
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

// `meadow bench` with the library of the scene from `libraryFor`: the full program builds it when
// missing (ensureLibrary), the bench runner (bench_main.cpp) only loads it (loadCachedLibrary).
struct Library;
struct Scene;
struct BenchLibrarySource {
    const char* usage; // the help's first line
    const char* note;  // where the library comes from, for the help
    std::function<Library(const Scene&)> libraryFor;
};
int runBenchWith(const Args& args, const BenchLibrarySource& source);

// True when `args` asks for help; prints `text` then.
bool printHelpIfAsked(const Args& args, const char* text);

} // namespace meadow
