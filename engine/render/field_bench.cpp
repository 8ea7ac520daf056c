#include "render/field_bench.h"

#include "core/error.h"
#include "render/cpu_driver.h"
#include "render/offscreen.h"
#include "render/render_targets.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>

namespace meadow {
namespace {

double percentile(std::vector<double> values, double p) {
    if (values.empty())
        return 0.0;
    std::sort(values.begin(), values.end());
    size_t index =
        static_cast<size_t>(std::min<double>(values.size() - 1, std::floor(p * double(values.size() - 1) + 0.5)));
    return values[index];
}

// One run of `options.frames` frames (after a warm-up) on either path; its figures as JSON.
nlohmann::json measure(Context& ctx, const std::vector<FieldClump>& clumps, const std::vector<gpu::GpuInstance>& field,
                       const RgbaImage& atlas, const FieldScenery& scenery, const FieldBenchOptions& options,
                       bool cpuDriven) {
    nlohmann::json j;
    FieldRenderer renderer = createFieldRenderer(ctx, clumps, field, atlas, scenery);
    if (cpuDriven)
        enableCpuDriver(ctx, renderer, clumps, field);
    // Only the LDR image is read, as in the window: the resolve stores nothing into the HDR image.
    Offscreen offscreen = createOffscreen(ctx, {options.width, options.height}, HdrContents::MeshPass);
    FrameState state;
    state.camera = options.camera;
    state.width = options.width;
    state.height = options.height;
    uint64_t uploadMin = UINT64_MAX, uploadMax = 0;
    uint32_t lightRuns = 0;
    std::vector<double> frameMs, cpuMs, lightMs, groundMapMs, lightFrameMs;
    std::map<std::string, std::vector<double>> passMs;
    for (uint32_t i = 0; i < kFieldBenchWarmUp + options.frames; ++i) {
        // A moving day, a minute of daylight per second (a day in 24 minutes): the light pass
        // runs every few frames.
        state.seconds = double(i) / 30.0 + 1e-6;
        state.hours = options.timeOfDay + state.seconds / 60.0;
        if (options.path)
            state.camera = cameraOnPath(options.camera, *options.path,
                                        double(i < kFieldBenchWarmUp ? 0 : i - kFieldBenchWarmUp) / 30.0);
        const uint64_t writtenBefore = ctx.hostBytesWritten;
        FrameTimings t = renderOffscreenFrame(ctx, renderer, offscreen, state);
        if (i < kFieldBenchWarmUp)
            continue;
        lightRuns += renderer.lightThisFrame ? 1 : 0;
        const uint64_t uploaded = ctx.hostBytesWritten - writtenBefore;
        uploadMin = std::min(uploadMin, uploaded);
        uploadMax = std::max(uploadMax, uploaded);
        frameMs.push_back(t.wallMs);
        cpuMs.push_back(t.cpuRecordSubmitMs);
        double total = 0.0, far = 0.0, light = 0.0;
        for (const PassTime& p : t.gpu) {
            passMs[p.label].push_back(p.milliseconds);
            total += p.milliseconds;
            if (p.label == "light" || p.label == "groundMap")
                light += p.milliseconds;
            if (p.label == "groundMap" && renderer.lightThisFrame)
                groundMapMs.push_back(p.milliseconds);
            if (p.label == "farSplat")
                far += p.milliseconds;
        }
        if (renderer.lightThisFrame) {
            lightMs.push_back(light);
            lightFrameMs.push_back(t.wallMs);
        }
        passMs["total"].push_back(total);
        if (renderer.farField)
            passMs["far"].push_back(far); // the splat pass (its resolve is the tone map pass)
    }
    FieldStats stats = readFieldStats(renderer);
    j["clumps"] = renderer.instanceCount;
    j["frameMs"] = {{"median", percentile(frameMs, 0.5)}, {"p95", percentile(frameMs, 0.95)}};
    nlohmann::json gpuMs = nlohmann::json::object();
    for (auto& [label, values] : passMs)
        gpuMs[label] = percentile(values, 0.5);
    j["gpuMs"] = gpuMs;
    // The light pass runs when the sky has moved enough (FieldRenderer::lightThisFrame): msWhenRun
    // is its two dispatches together (light.comp, then the ground light map's gather, timed alone
    // as groundMapMsWhenRun); frameMsWhenRun is the median frame among those that ran it.
    j["lightPass"] = {{"framesRun", lightRuns},
                      {"msWhenRun", percentile(lightMs, 0.5)},
                      {"frameMsWhenRun", percentile(lightFrameMs, 0.5)},
                      {"groundMapMsWhenRun", percentile(groundMapMs, 0.5)}};
    // Recording and submitting, plus (CPU-driven) stepping, culling and filling the uploads.
    j["cpuMsPerFrame"] = percentile(cpuMs, 0.5);
    // Every byte the CPU wrote for the device during the frame (Context::hostBytesWritten): the
    // uniform block and the push constants, plus (CPU-driven) the visible instances' draw
    // records, the draw commands, the statistics and the visible lists.
    j["uploadBytesPerFrame"] = uploadMax;
    j["uploadBytesPerFrameMin"] = uploadMin;
    j["trianglesPerFrame"] = stats.trianglesDrawn;
    // Draws per LOD over all clumps (a crossfading instance counts in both of its LODs), whether the
    // mesh pass or the near raster drew them.
    j["instancesPerLod"] = stats.drawsPerLod();
    // Where each coarser LOD takes over (px of projected radius; --lod-tolerance scales them).
    std::vector<float> switchRadii;
    for (uint32_t i = 0; i + 1 < renderer.lodCount; ++i)
        switchRadii.push_back(renderer.lodParams.switchRadius[i]);
    j["lodSwitchRadii"] = switchRadii;
    j["visibleInstances"] = stats.visibleInstances;
    // The far field (--far-radius): instances drawn as surface samples (a crossfading one counts
    // here and at the mesh LOD it fades from) and the splats they drew, in the last measured frame.
    j["farRadius"] = renderer.farField ? renderer.lodParams.farRadius : 0.0f;
    j["instancesFar"] = stats.farInstances;
    j["splatsPerFrame"] = stats.farSamples;
    // The near raster (--near-raster): the LOD draws it took from the mesh pass and their triangles
    // (not in trianglesPerFrame).
    j["nearRaster"] = renderer.nearRasterOn;
    j["nearRasterDraws"] = stats.nearInstances;
    j["nearRasterTriangles"] = stats.nearTriangles;
    if (options.lastFrameRgba && cpuDriven == options.cpuDriven)
        *options.lastFrameRgba = readLdrPixels(ctx, offscreen.targets);
    destroyOffscreen(ctx, offscreen);
    destroyFieldRenderer(ctx, renderer);
    return j;
}

} // namespace

std::vector<gpu::GpuInstance> tileField(const std::vector<gpu::GpuInstance>& field, uint32_t count) {
    if (field.empty())
        throw Error("the field has no clumps to tile");
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const gpu::GpuInstance& inst : field) {
        lo = glm::min(lo, glm::vec3(inst.positionScale));
        hi = glm::max(hi, glm::vec3(inst.positionScale));
    }
    const glm::vec3 extent = hi - lo + glm::vec3(1.0f);
    // Copies on a square grid of odd side around the field itself, taken ring by ring outwards
    // (within a ring row by row), so that the field stays where the scene's camera looks and the
    // copies grow around it: any count shows the view the default field shows, then more beyond.
    const uint64_t copies = (uint64_t(count) + field.size() - 1) / field.size();
    int64_t half = 0;
    while (uint64_t(2 * half + 1) * uint64_t(2 * half + 1) < copies)
        ++half;
    std::vector<glm::ivec2> cells;
    for (int64_t z = -half; z <= half; ++z)
        for (int64_t x = -half; x <= half; ++x)
            cells.emplace_back(int(x), int(z));
    std::stable_sort(cells.begin(), cells.end(), [](glm::ivec2 a, glm::ivec2 b) {
        return std::max(std::abs(a.x), std::abs(a.y)) < std::max(std::abs(b.x), std::abs(b.y));
    });
    std::vector<gpu::GpuInstance> out;
    out.reserve(count);
    for (size_t t = 0; out.size() < count; ++t) {
        const glm::vec3 offset(extent.x * float(cells[t].x), 0.0f, extent.z * float(cells[t].y));
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

Camera cameraOnPath(Camera lens, const CameraPath& path, double seconds) {
    const CameraPose pose = sampleCameraPath(path, path.startTime() + seconds);
    lens.eye = pose.eye;
    lens.target = pose.target;
    return lens;
}

nlohmann::json benchmarkField(Context& ctx, const std::vector<FieldClump>& clumps,
                              const std::vector<gpu::GpuInstance>& field, const RgbaImage& atlas,
                              const FieldScenery& scenery, const FieldBenchOptions& options) {
    nlohmann::json j = measure(ctx, clumps, field, atlas, scenery, options, options.cpuDriven);
    j["device"] = ctx.deviceName();
    j["driver"] = options.cpuDriven ? "cpu" : "gpu";
    j["vulkanDriver"] = ctx.driverDescription();
    j["width"] = options.width;
    j["height"] = options.height;
    j["frames"] = options.frames;
    j["instanceRecordBytes"] =
        sizeof(gpu::GpuInstance) + sizeof(gpu::GpuMotionState) + sizeof(float); // + LOD coordinate
    if (options.cpuDriven) {
        // The GPU-driven path in the same run, for the ratio (docs/BENCHMARKS.md, The numbers
        // meadow holds itself to).
        nlohmann::json gpu = measure(ctx, clumps, field, atlas, scenery, options, false);
        j["comparison"] = {
            {"gpuDriven", gpu},
            {"cpuTimeRatio", j["cpuMsPerFrame"].get<double>() / std::max(gpu["cpuMsPerFrame"].get<double>(), 1e-9)},
            {"uploadRatio", double(j["uploadBytesPerFrame"].get<uint64_t>()) /
                                double(std::max<uint64_t>(gpu["uploadBytesPerFrame"].get<uint64_t>(), 1))}};
    }
    return j;
}

} // namespace meadow
