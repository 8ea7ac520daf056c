// meadow-bench: `meadow bench` without the rest of meadow, for machines that have a GPU but not
// meadow's build dependencies (scripts/bundle-bench.sh carries it there with the libraries it
// needs). It loads the scene's library from the cache and never builds one, so it links neither the
// precompute stages (Embree, Eigen) nor the window or image libraries (GLFW, OpenImageIO).
#include "app/commands.h"
#include "core/error.h"
#include "pipeline/build_library.h"

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    using namespace meadow;
    Args args(argv + 1, argv + argc);
    try {
        return runBenchWith(args, {"usage: meadow-bench SCENE --json OUT [options]",
                                   "The bench runner: meadow bench with the scene's library taken from the cache\n"
                                   "($MEADOW_CACHE_DIR, else ~/.cache/meadow) as `meadow precompute` left it;\n"
                                   "it never builds one.\n",
                                   [](const Scene& scene) { return loadCachedLibrary(scene); }});
    } catch (const Error& e) {
        std::fprintf(stderr, "meadow-bench: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "meadow-bench: internal error: %s\n", e.what());
        return 1;
    }
}
