// meadow precompute / meadow inspect.
#include "app/commands.h"
#include "app/session.h"
#include "core/error.h"

#include <cstdio>
#include <fstream>

namespace meadow {
namespace {

const char* kPrecomputeHelp = R"(usage: meadow precompute SCENE [--preset ci|full] [--seed S] [--out LIB]

Builds the library of SCENE (a scene JSON file) and writes it to LIB, by default to the
library cache ($MEADOW_CACHE_DIR, else ~/.cache/meadow). Prints the library's path.
)";

const char* kInspectHelp = R"(usage: meadow inspect LIB --json

Checks a library file and prints facts about it as JSON on stdout.
)";

} // namespace

int runPrecompute(const Args& argv) {
    if (printHelpIfAsked(argv, kPrecomputeHelp))
        return 0;
    CommandSpec spec{"precompute", {"SCENE"}, {"--out"}, {}};
    addSceneOptions(spec);
    ParsedArgs args = parseArgs(spec, argv);
    Scene scene = sceneFromArgs(args);
    std::filesystem::path out = args.value("--out").value_or(cachedLibraryPath(scene).string());
    std::error_code ec;
    if (out.has_parent_path() && !std::filesystem::is_directory(out.parent_path(), ec)) {
        if (args.has("--out"))
            throw Error("meadow precompute: --out " + out.string() + ": folder " + out.parent_path().string() +
                        " does not exist");
        std::filesystem::create_directories(out.parent_path(), ec);
        if (ec)
            throw Error("cannot create the library cache folder " + out.parent_path().string() + ": " + ec.message());
    }
    buildLibrary(scene, out);
    loadLibrary(out); // what was written must read back
    std::printf("%s\n", out.string().c_str());
    return 0;
}

int runInspect(const Args& argv) {
    if (printHelpIfAsked(argv, kInspectHelp))
        return 0;
    CommandSpec spec{"inspect", {"LIB"}, {}, {"--json"}};
    ParsedArgs args = parseArgs(spec, argv);
    if (!args.has("--json"))
        throw Error("meadow inspect: only JSON output exists; pass --json");
    Library lib = loadLibrary(args.positionals[0]);

    nlohmann::json j;
    j["formatVersion"] = lib.formatVersion;
    j["inputHash"] = lib.inputHash;
    j["bytes"] = lib.fileBytes;
    j["sections"] = lib.sections;
    j["scene"] = {{"name", lib.scene.value("name", "")}, {"seed", lib.scene.value("seed", 0)}};
    j["testField"] = {{"instances", lib.testField.size()},
                      {"meshVertices", lib.testMesh.vertices.size()},
                      {"meshTriangles", lib.testMesh.indices.size() / 3}};
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
}

} // namespace meadow
