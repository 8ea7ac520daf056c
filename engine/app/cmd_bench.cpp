// meadow bench, and the bench runner (bench_main.cpp) that shares its command line: timings of a
// scene's field as JSON (render/field_bench.h).
#include "app/commands.h"
#include "app/session.h"
#include "core/error.h"
#include "io/output_path.h"
#include "render/field_bench.h"
#include "render/field_content.h"

#include <cstdio>
#include <fstream>
#include <string_view>

namespace meadow {
namespace {

// Writes `bytes` to `path` whole or not at all (a temporary file beside it, renamed into place).
void writeWhole(const std::filesystem::path& path, std::string_view bytes) {
    std::filesystem::path tmp = path;
    tmp += ".partial";
    {
        std::ofstream file(tmp, std::ios::binary);
        file.write(bytes.data(), std::streamsize(bytes.size()));
        if (!file) {
            file.close();
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw Error("cannot write " + path.string());
        }
    }
    std::filesystem::rename(tmp, path);
}

const char* kBenchOptions = R"(
Renders frames offscreen and writes timings as JSON to OUT: frame times, CPU time per frame,
GPU time per pass from timestamps, bytes uploaded per frame, triangles and instances drawn.

options:
  --clumps N            clumps in the field: the scene's clumps are tiled (or cut) to N, without
                        the rocks
  --frames F            measured frames (default 120), after 5 warm-up frames
  --camera EX,EY,EZ,TX,TY,TZ   eye and target in metres (default: the scene's)
  --camera-path FILE    measured frame i sees the camera path at i/30 s (warm-up: its start)
  --size WxH            image size (default 1280x720)
  --driver gpu|cpu      gpu (default): the compute passes animate, cull and pick LODs; cpu: the
                        CPU does (render/cpu_driver.h) and uploads the results every frame, and
                        the GPU-driven path runs after it for the ratio ("comparison")
  --frame-rgba FILE     also writes the last measured frame as raw pixels: WxH of 8-bit sRGB
                        RGBA, rows top to bottom, no header (the runner links no image library;
                        a picture to check on a machine that has only the bundle)
)";

} // namespace

int runBenchWith(const Args& argv, const BenchLibrarySource& source) {
    const std::string help =
        std::string(source.usage) + "\n" + source.note + kBenchOptions + kFieldOptionsHelp + kSceneAndEngineOptionsHelp;
    if (printHelpIfAsked(argv, help.c_str()))
        return 0;
    CommandSpec spec{
        "bench",
        {"SCENE"},
        {"--json", "--clumps", "--frames", "--size", "--driver", "--camera", "--camera-path", "--frame-rgba"},
        {}};
    addSceneOptions(spec);
    addEngineOptions(spec);
    addFieldOptions(spec);
    ParsedArgs args = parseArgs(spec, argv);
    const FieldOptions fieldOptions = fieldOptionsFromArgs(args);

    // Everything about the command line and the output is checked before any work starts.
    if (!args.has("--json"))
        throw Error("meadow bench: --json OUT is required");
    std::filesystem::path out = *args.value("--json");
    checkOutputWritable(out);
    std::optional<std::filesystem::path> frameOut;
    if (args.has("--frame-rgba")) {
        frameOut = *args.value("--frame-rgba");
        checkOutputWritable(*frameOut);
    }
    const std::string driver = args.value("--driver").value_or("gpu");
    if (driver != "gpu" && driver != "cpu")
        throw Error("meadow bench: --driver '" + driver + "' is not gpu or cpu");
    FieldBenchOptions options;
    options.cpuDriven = driver == "cpu";
    options.frames = args.u32("--frames", 120, 1, 1000000);
    std::tie(options.width, options.height) = args.size("--size", {1280, 720});
    options.path = cameraPathFromArgs(args);
    std::vector<uint8_t> frame;
    if (frameOut)
        options.lastFrameRgba = &frame;
    std::optional<uint32_t> clumpCount;
    if (args.has("--clumps"))
        clumpCount = args.u32("--clumps", 0, 1, 50'000'000);
    const Scene scene = sceneFromArgs(args);
    options.camera = cameraFromArgs(args, scene);
    options.timeOfDay = scene.timeOfDay;

    const Library library = source.libraryFor(scene);
    // The field with its rocks; --clumps tiles the clumps alone (the rocks are left out).
    const std::vector<gpu::GpuInstance> field =
        clumpCount ? tileField(library.field.clumpInstances, *clumpCount) : fieldInstances(library);
    std::vector<FieldClump> clumps = fieldClumps(library);
    FieldScenery scenery = fieldScenery(library, fieldOptions.lodTolerance);
    applyFieldOptions(fieldOptions, clumps, scenery);

    Context ctx;
    createContext(ctx, contextOptionsFromArgs(args));
    nlohmann::json j = benchmarkField(ctx, clumps, field, library.atlas, scenery, options);
    j["scene"] = scene.name;
    j["preset"] = scene.preset;
    if (options.path)
        j["cameraPath"] = *args.value("--camera-path");
    const int status = validationExitStatus(ctx);
    destroyContext(ctx);

    if (frameOut)
        writeWhole(*frameOut, std::string_view(reinterpret_cast<const char*>(frame.data()), frame.size()));
    writeWhole(out, j.dump(2) + "\n");
    std::printf("%s\n", j.dump(2).c_str());
    return status;
}

} // namespace meadow
