// The benchmark behind `meadow bench` and the bench runner (engine/app/bench_main.cpp): frames of a
// field offscreen under a moving sky, timed per pass with GPU timestamps, as JSON
// (docs/INTERFACE.md, bench --json).
#pragma once

#include "render/camera.h"
#include "render/camera_path.h"
#include "render/field_renderer.h"
#include "vk/context.h"

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

namespace meadow {

struct FieldBenchOptions {
    uint32_t frames = 120; // measured, after kFieldBenchWarmUp frames
    uint32_t width = 1280, height = 720;
    bool cpuDriven = false;         // the CPU-driven path first, then the GPU-driven one for the ratios
    Camera camera;                  // the lens, and the view when there is no path
    float timeOfDay = 12.0f;        // at the first frame; the sky then moves a minute per second
    std::optional<CameraPath> path; // measured frame i sees it at i/30 s
    // When set, receives the last measured frame of the path asked for (cpuDriven's), tonemapped:
    // width x height pixels of 8-bit sRGB RGBA, rows top to bottom.
    std::vector<uint8_t>* lastFrameRgba = nullptr;
};

inline constexpr uint32_t kFieldBenchWarmUp = 5;

// The field's instances tiled (or cut) to `count`: the field itself first, where it lies, then
// whole copies side by side around it, nearest first (a square grid, ring by ring).
std::vector<gpu::GpuInstance> tileField(const std::vector<gpu::GpuInstance>& field, uint32_t count);

// The camera `lens` (field of view and planes) at the path's pose `seconds` after its start.
Camera cameraOnPath(Camera lens, const CameraPath& path, double seconds);

// Runs the benchmark on `ctx` and returns its figures: frameMs (median, p95), gpuMs per pass
// (median), lightPass, cpuMsPerFrame, upload bytes per frame, triangles, instances per LOD and, with
// cpuDriven, "comparison" (the GPU-driven run and the CPU-time and upload ratios). The caller adds
// what it knows of the scene.
nlohmann::json benchmarkField(Context& ctx, const std::vector<FieldClump>& clumps,
                              const std::vector<gpu::GpuInstance>& field, const RgbaImage& atlas,
                              const FieldScenery& scenery, const FieldBenchOptions& options);

} // namespace meadow
