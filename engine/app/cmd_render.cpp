// meadow render / meadow bench: offscreen frames of a scene.
#include "app/commands.h"
#include "app/session.h"
#include "core/error.h"
#include "io/image_io.h"
#include "render/camera_path.h"
#include "render/cpu_driver.h"
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
  --preset ci|full      scene preset (default full)
  --seed S              override the scene's seed
  --device N|NAME       Vulkan device by index or part of its name (or MEADOW_DEVICE)
  --validation          run under the Khronos validation layer, synchronization validation
                        included (or MEADOW_VALIDATION=1); exits 3 if it reports anything
  --verbose             say which device is used
)";

const char* kBenchHelp = R"(usage: meadow bench SCENE --json OUT [options]

Renders frames offscreen and writes timings as JSON to OUT: frame times, CPU time per frame,
GPU time per pass from timestamps, bytes uploaded per frame, triangles and instances drawn.

options:
  --clumps N            clumps in the field: the scene's clumps are tiled (or cut) to N, without
                        the rocks
  --frames F            measured frames (default 120), after 5 warm-up frames
  --camera-path FILE    measured frame i sees the camera path at i/30 s (warm-up: its start)
  --size WxH            image size (default 1280x720)
  --driver gpu|cpu      gpu (default): the compute passes animate, cull and pick LODs; cpu: the
                        CPU does (render/cpu_driver.h) and uploads the results every frame, and
                        the GPU-driven path runs after it for the ratio ("comparison")
  --preset, --seed, --device, --validation, --verbose   as for meadow render
)";

// The field's instances tiled (or cut) to `count`: copies of the whole field side by side.
std::vector<gpu::GpuInstance> tileField(const std::vector<gpu::GpuInstance>& field, uint32_t count) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const gpu::GpuInstance& inst : field) {
        lo = glm::min(lo, glm::vec3(inst.positionScale));
        hi = glm::max(hi, glm::vec3(inst.positionScale));
    }
    glm::vec3 extent = hi - lo + glm::vec3(1.0f);
    uint32_t tiles = static_cast<uint32_t>((count + field.size() - 1) / field.size());
    uint32_t side = static_cast<uint32_t>(std::ceil(std::sqrt(double(tiles))));
    std::vector<gpu::GpuInstance> out;
    out.reserve(count);
    for (uint32_t t = 0; out.size() < count; ++t) {
        glm::vec3 offset(extent.x * (float(t % side) - float(side - 1) * 0.5f), 0.0f,
                         extent.z * (float(t / side) - float(side - 1) * 0.5f));
        for (const gpu::GpuInstance& inst : field) {
            if (out.size() == count)
                break;
            gpu::GpuInstance copy = inst;
            copy.positionScale += glm::vec4(offset, 0.0f);
            out.push_back(copy);
        }
    }
    return out;
}

// --camera-path FILE, loaded and checked before any work; it and --camera both set the camera.
std::optional<CameraPath> cameraPathFromArgs(const ParsedArgs& args) {
    std::optional<std::string> file = args.value("--camera-path");
    if (!file)
        return std::nullopt;
    if (args.has("--camera"))
        throw Error("meadow " + args.command + ": --camera and --camera-path both set the camera; give one");
    return loadCameraPath(*file);
}

// `lens` (the scene's field of view and planes) at the path's pose `seconds` after its start.
Camera cameraOnPath(Camera lens, const CameraPath& path, double seconds) {
    const CameraPose pose = sampleCameraPath(path, path.startTime() + seconds);
    lens.eye = pose.eye;
    lens.target = pose.target;
    return lens;
}

double percentile(std::vector<double> values, double p) {
    if (values.empty())
        return 0.0;
    std::sort(values.begin(), values.end());
    size_t index =
        static_cast<size_t>(std::min<double>(values.size() - 1, std::floor(p * double(values.size() - 1) + 0.5)));
    return values[index];
}

} // namespace

int runRender(const Args& argv) {
    if (printHelpIfAsked(argv, kRenderHelp))
        return 0;
    CommandSpec spec{"render",
                     {"SCENE"},
                     {"--out", "--frames", "--size", "--time-of-day", "--camera", "--camera-path", "--wind"},
                     {}};
    spec.switchOptions.insert("--debug-lod");
    addSceneOptions(spec);
    addEngineOptions(spec);
    ParsedArgs args = parseArgs(spec, argv);

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
        FieldRenderer renderer = createFieldRenderer(ctx, fieldClumps(library), fieldInstances(library), library.atlas,
                                                     fieldScenery(library));
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
        std::fprintf(stderr, "meadow: rendered %u frame%s of %s at %ux%u on %s: %u of %u instances visible\n", frames,
                     frames == 1 ? "" : "s", scene.name.c_str(), width, height, ctx.deviceName().c_str(),
                     stats.visibleInstances, stats.testedInstances);
        destroyOffscreen(ctx, offscreen);
        destroyFieldRenderer(ctx, renderer);
    }
    status = validationExitStatus(ctx);
    destroyContext(ctx);
    return status;
}

int runBench(const Args& argv) {
    if (printHelpIfAsked(argv, kBenchHelp))
        return 0;
    CommandSpec spec{"bench", {"SCENE"}, {"--json", "--clumps", "--frames", "--size", "--driver", "--camera-path"}, {}};
    addSceneOptions(spec);
    addEngineOptions(spec);
    ParsedArgs args = parseArgs(spec, argv);
    if (!args.has("--json"))
        throw Error("meadow bench: --json OUT is required");
    std::filesystem::path out = *args.value("--json");
    checkOutputWritable(out);
    std::string driver = args.value("--driver").value_or("gpu");
    if (driver != "gpu" && driver != "cpu")
        throw Error("meadow bench: --driver '" + driver + "' is not gpu or cpu");
    uint32_t frames = args.u32("--frames", 120, 1, 1000000);
    auto [width, height] = args.size("--size", {1280, 720});
    const std::optional<CameraPath> path = cameraPathFromArgs(args);
    Scene scene = sceneFromArgs(args);
    Library library = ensureLibrary(scene);
    // The field with its rocks; --clumps tiles the clumps alone (the rocks are left out).
    std::vector<gpu::GpuInstance> field = fieldInstances(library);
    if (args.has("--clumps"))
        field = tileField(library.field, args.u32("--clumps", 0, 1, 50'000'000));
    Camera camera = cameraFromArgs(args, scene);
    const std::vector<FieldClump> clumps = fieldClumps(library);
    const FieldScenery scenery = fieldScenery(library);

    Context ctx;
    createContext(ctx, contextOptionsFromArgs(args));
    // One run of `frames` frames (after a warm-up) on either path; its figures as JSON.
    auto measure = [&](bool cpuDriven) {
        nlohmann::json j;
        FieldRenderer renderer = createFieldRenderer(ctx, clumps, field, library.atlas, scenery);
        if (cpuDriven)
            enableCpuDriver(ctx, renderer, clumps, field);
        Offscreen offscreen = createOffscreen(ctx, {width, height});
        FrameState state;
        state.camera = camera;
        state.width = width;
        state.height = height;
        uint64_t uploadMin = UINT64_MAX, uploadMax = 0;
        uint32_t lightRuns = 0;
        std::vector<double> frameMs, cpuMs, lightMs;
        std::map<std::string, std::vector<double>> passMs;
        const uint32_t warmup = 5;
        for (uint32_t i = 0; i < warmup + frames; ++i) {
            // A moving day, a minute of daylight per second (a day in 24 minutes): the light pass
            // runs every few frames.
            state.seconds = double(i) / 30.0 + 1e-6;
            state.hours = scene.timeOfDay + state.seconds / 60.0;
            if (path)
                state.camera = cameraOnPath(camera, *path, double(i < warmup ? 0 : i - warmup) / 30.0);
            FrameTimings t = renderOffscreenFrame(ctx, renderer, offscreen, state);
            if (i < warmup)
                continue;
            lightRuns += renderer.lightThisFrame ? 1 : 0;
            uploadMin = std::min(uploadMin, renderer.uploadBytesLastFrame);
            uploadMax = std::max(uploadMax, renderer.uploadBytesLastFrame);
            frameMs.push_back(t.wallMs);
            cpuMs.push_back(t.cpuRecordSubmitMs);
            double total = 0.0;
            for (const PassTime& p : t.gpu) {
                passMs[p.label].push_back(p.milliseconds);
                total += p.milliseconds;
                if (p.label == "light" && renderer.lightThisFrame)
                    lightMs.push_back(p.milliseconds);
            }
            passMs["total"].push_back(total);
        }
        FieldStats stats = readFieldStats(renderer);
        j["clumps"] = renderer.instanceCount;
        j["frameMs"] = {{"median", percentile(frameMs, 0.5)}, {"p95", percentile(frameMs, 0.95)}};
        nlohmann::json gpuMs = nlohmann::json::object();
        for (auto& [label, values] : passMs)
            gpuMs[label] = percentile(values, 0.5);
        j["gpuMs"] = gpuMs;
        // The light pass runs when the sky has moved enough (FieldRenderer::lightThisFrame).
        j["lightPass"] = {{"framesRun", lightRuns}, {"msWhenRun", percentile(lightMs, 0.5)}};
        // Recording and submitting, plus (CPU-driven) stepping, culling and filling the uploads.
        j["cpuMsPerFrame"] = percentile(cpuMs, 0.5);
        // The uniform block and the push constants recorded into each frame (FieldRenderer), plus
        // (CPU-driven) the motion states, LOD coordinates, draw commands and visible lists.
        j["uploadBytesPerFrame"] = uploadMax;
        j["uploadBytesPerFrameMin"] = uploadMin;
        j["trianglesPerFrame"] = stats.trianglesDrawn;
        // Draws per LOD over all clumps (a crossfading instance counts in both of its LODs).
        std::vector<uint32_t> perLod(renderer.lodCount, 0);
        for (size_t m = 0; m < stats.visiblePerMesh.size(); ++m)
            perLod[m % renderer.lodCount] += stats.visiblePerMesh[m];
        j["instancesPerLod"] = perLod;
        j["visibleInstances"] = stats.visibleInstances;
        destroyOffscreen(ctx, offscreen);
        destroyFieldRenderer(ctx, renderer);
        return j;
    };
    nlohmann::json j = measure(driver == "cpu");
    j["device"] = ctx.deviceName();
    j["driver"] = driver;
    j["vulkanDriver"] = ctx.driverDescription();
    j["scene"] = scene.name;
    j["preset"] = scene.preset;
    j["width"] = width;
    j["height"] = height;
    j["frames"] = frames;
    if (path)
        j["cameraPath"] = *args.value("--camera-path");
    j["instanceRecordBytes"] =
        sizeof(gpu::GpuInstance) + sizeof(gpu::GpuMotionState) + sizeof(float); // + LOD coordinate
    if (driver == "cpu") {
        // The GPU-driven path in the same run, for the ratio (DESIGN.md 5).
        nlohmann::json gpu = measure(false);
        j["comparison"] = {
            {"gpuDriven", gpu},
            {"cpuTimeRatio", j["cpuMsPerFrame"].get<double>() / std::max(gpu["cpuMsPerFrame"].get<double>(), 1e-9)},
            {"uploadRatio", double(j["uploadBytesPerFrame"].get<uint64_t>()) /
                                double(std::max<uint64_t>(gpu["uploadBytesPerFrame"].get<uint64_t>(), 1))}};
    }
    int status = validationExitStatus(ctx);
    destroyContext(ctx);

    std::filesystem::path tmp = out;
    tmp += ".partial";
    {
        std::ofstream file(tmp);
        file << j.dump(2) << "\n";
        if (!file)
            throw Error("cannot write " + out.string());
    }
    std::filesystem::rename(tmp, out);
    std::printf("%s\n", j.dump(2).c_str());
    return status;
}

} // namespace meadow
