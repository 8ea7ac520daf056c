// meadow render: offscreen frames of a scene.
#include "app/commands.h"
#include "app/session.h"
#include "core/error.h"
#include "io/image_io.h"
#include "render/field_bench.h"
#include "render/offscreen.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <unistd.h>

namespace meadow {
namespace {

const char* kRenderHelp = R"(usage: meadow render SCENE --out FILE [options]

Renders frames of SCENE offscreen and writes them as PNG (tonemapped, 8-bit sRGB) or EXR
(linear half-float radiance), by FILE's extension. Builds the scene's library first if the
cache lacks it. With --frames N > 1, frame i goes to FILE with .NNNN before the extension.

options:
  --out FILE            output image (.png or .exr)
  --frames N            frames to render, 1/30 s apart (default 1), after 2 s of motion in the
                        wind so the first frame already sways in it
  --size WxH            image size (default 1280x720)
  --time-of-day H       local solar hour, 0-24 (default: the scene's)
  --wind L              base wind level, 0 (calm) to the scene's top level (default 1.2); waves
                        and gusts travel over it
  --debug-lod           colour each clump by its level of detail
  --camera EX,EY,EZ,TX,TY,TZ   eye and target in metres (default: the scene's)
  --camera-path FILE    a camera path (JSON keyframes, as meadow view records): frame i sees the
                        path at i/30 s; without --frames, every frame of the path is rendered
)";

} // namespace

int runRender(const Args& argv) {
    if (printHelpIfAsked(argv, (std::string(kRenderHelp) + kFieldOptionsHelp + kSceneAndEngineOptionsHelp).c_str()))
        return 0;
    CommandSpec spec{"render",
                     {"SCENE"},
                     {"--out", "--frames", "--size", "--time-of-day", "--camera", "--camera-path", "--wind"},
                     {}};
    spec.switchOptions.insert("--debug-lod");
    addSceneOptions(spec);
    addEngineOptions(spec);
    addFieldOptions(spec);
    ParsedArgs args = parseArgs(spec, argv);
    const FieldOptions fieldOptions = fieldOptionsFromArgs(args);

    // Everything about the output is checked before any work starts.
    if (!args.has("--out"))
        throw Error("meadow render: --out FILE is required");
    std::filesystem::path out = *args.value("--out");
    ImageFileKind kind = imageKindForPath(out);
    checkOutputWritable(out);
    const std::optional<CameraPath> path = cameraPathFromArgs(args);
    const uint32_t pathFrames = path ? uint32_t(std::floor(path->duration() * 30.0 + 1e-6)) + 1 : 1;
    uint32_t frames = args.u32("--frames", pathFrames, 1, 100000);
    auto [width, height] = args.size("--size", {1280, 720});
    Scene scene = sceneFromArgs(args);
    float timeOfDay = args.f32("--time-of-day", scene.timeOfDay, 0.0f, 24.0f);
    Camera camera = cameraFromArgs(args, scene);
    WindState wind;
    const float topLevel = float(scene.wind.levelSpeeds.size() - 1);
    wind.baseLevel = args.f32("--wind", std::min(wind.baseLevel, topLevel), 0.0f, topLevel);

    Library library = ensureLibrary(scene);

    Context ctx;
    createContext(ctx, contextOptionsFromArgs(args));
    int status = 0;
    {
        FieldScenery scenery = fieldScenery(library, fieldOptions.lodTolerance);
        std::vector<FieldClump> clumps = fieldClumps(library);
        applyFieldOptions(fieldOptions, clumps, scenery);
        FieldRenderer renderer = createFieldRenderer(ctx, clumps, fieldInstances(library), library.atlas, scenery);
        Offscreen offscreen = createOffscreen(ctx, {width, height});
        FrameState state;
        state.camera = path ? cameraOnPath(camera, *path, 0.0) : camera;
        state.width = width;
        state.height = height;
        state.hours = timeOfDay;
        state.wind = wind;
        state.debugView = args.has("--debug-lod") ? gpu::kDebugViewLod : gpu::kDebugViewNone;
        const double warmUp = 2.0;
        state.seconds = warmUp;
        advanceMotion(ctx, renderer, state);
        for (uint32_t i = 0; i < frames; ++i) {
            state.seconds = warmUp + double(i) / 30.0 + 1e-6;
            if (path)
                state.camera = cameraOnPath(camera, *path, double(i) / 30.0);
            renderOffscreenFrame(ctx, renderer, offscreen, state);
            std::filesystem::path path = framePath(out, i, frames);
            if (kind == ImageFileKind::Png)
                writeRgba8(path, width, height, readLdrPixels(ctx, offscreen.targets));
            else
                writeRgbaHalf(path, width, height, readHdrPixels(ctx, offscreen.targets));
        }
        FieldStats stats = readFieldStats(renderer);
        std::fprintf(stderr,
                     "meadow: rendered %u frame%s of %s at %ux%u on %s: %u of %u instances visible, %u in the far "
                     "field (%u splats)\n",
                     frames, frames == 1 ? "" : "s", scene.name.c_str(), width, height, ctx.deviceName().c_str(),
                     stats.visibleInstances, stats.testedInstances, stats.farInstances, stats.farSamples);
        destroyOffscreen(ctx, offscreen);
        destroyFieldRenderer(ctx, renderer);
    }
    status = validationExitStatus(ctx);
    destroyContext(ctx);
    return status;
}

// The bench's command line and figures are cmd_bench.cpp's; this program builds a missing library.
int runBench(const Args& args) {
    return runBenchWith(args, {"usage: meadow bench SCENE --json OUT [options]",
                               "Builds the scene's library first if the cache lacks it.\n",
                               [](const Scene& scene) { return ensureLibrary(scene); }});
}

} // namespace meadow
