// The HUD's panels: what every pass costs (frames per second, GPU time per pass from timestamps,
// visible instances per LOD, triangles) and the controls (wind, time of day, debug views,
// camera, window), plus the key help. ImGui widgets only; hud.h draws them.
#pragma once

#include "ui/fly_camera.h"
#include "ui/view_controls.h"
#include "vk/timestamps.h"

#include <string>
#include <vector>

namespace meadow {

struct HudStats {
    double fps = 0.0;          // frames per second over the last half second or so
    double cpuFrameMs = 0.0;   // wall time per frame, the same window
    std::vector<PassTime> gpu; // per pass, averaged over the same window
    double gpuTotalMs = 0.0;
    uint32_t visibleInstances = 0, testedInstances = 0;
    std::vector<uint32_t> instancesPerLod; // a crossfading instance counts in both of its LODs
    float farRadius = 0.0f;                // px; 0: the far field is off (--far-radius 0)
    uint32_t farInstances = 0;             // drawn as the far field's splats (a crossfading one counts)
    uint64_t farSamples = 0;               // their samples splatted
    uint64_t triangles = 0;                // the draw pass's (graphics pipeline), terrain and sky included
    bool nearRaster = false;               // whether the near raster is on (--near-raster)
    uint32_t nearDraws = 0;                // LOD draws it took (a crossfading instance may have two)
    uint64_t nearTriangles = 0;            // their triangles (not in `triangles`)
    std::string device;
    uint32_t width = 0, height = 0;
    const char* presentMode = "";
    bool hasPath = false, playing = false;
    double pathTime = 0.0, pathDuration = 0.0;
    bool canRecord = false, recording = false;
    size_t recordedKeyframes = 0;
    std::string lastScreenshot;
    bool scripted = false;
};

void drawHudPanels(ViewControls& controls, ViewRequests& requests, FlyCamera& camera, const HudStats& stats);

} // namespace meadow
