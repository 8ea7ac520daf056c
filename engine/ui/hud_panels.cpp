#include "ui/hud_panels.h"

#include <algorithm>
#include <cstring>
#include <imgui.h>

namespace meadow {
namespace {

void statsSection(const HudStats& s) {
    ImGui::Text("%.1f fps   %.1f ms per frame", s.fps, s.cpuFrameMs);
    ImGui::TextUnformatted(s.device.c_str());
    ImGui::Text("%ux%u, present mode %s", s.width, s.height, s.presentMode);
    // Label and time in columns of the (monospaced) font's characters, padded to the longest label:
    // a table's fixed first column stayed too narrow for the near raster's labels and cut them.
    int labelWidth = int(std::strlen("GPU total"));
    for (const PassTime& p : s.gpu)
        labelWidth = std::max(labelWidth, int(p.label.size()));
    for (const PassTime& p : s.gpu)
        ImGui::Text("%-*s %7.2f ms", labelWidth, p.label.c_str(), p.milliseconds);
    ImGui::Text("%-*s %7.2f ms", labelWidth, "GPU total", s.gpuTotalMs);
    ImGui::Text("%u of %u instances visible", s.visibleInstances, s.testedInstances);
    for (size_t lod = 0; lod < s.instancesPerLod.size(); ++lod) {
        if (lod > 0)
            ImGui::SameLine();
        ImGui::Text("LOD%zu %u", lod, s.instancesPerLod[lod]);
    }
    ImGui::Text("%.2f M triangles per frame in the draw pass", double(s.triangles) * 1e-6);
    if (s.nearRaster)
        ImGui::Text("near raster: %u draws, %.2f M triangles", s.nearDraws, double(s.nearTriangles) * 1e-6);
    if (s.farRadius > 0.0f)
        ImGui::Text("far field (below %.0f px): %u instances, %.2f M splats", s.farRadius, s.farInstances,
                    double(s.farSamples) * 1e-6);
    else
        ImGui::TextUnformatted("far field off (--far-radius 0)");
}

void windSection(ViewControls& c) {
    ImGui::SliderFloat("base level", &c.wind.baseLevel, 0.0f, c.topWindLevel, "%.2f");
    ImGui::SliderFloat("wave amplitude", &c.wind.waveAmplitude, 0.0f, c.topWindLevel, "%.2f levels");
    ImGui::SliderFloat("wavelength", &c.wind.wavelength, 2.0f, 200.0f, "%.0f m");
    ImGui::SliderFloat("wave speed", &c.wind.waveSpeed, 0.0f, 30.0f, "%.1f m/s");
    ImGui::SliderFloat("gusts", &c.wind.gustAmplitude, 0.0f, c.topWindLevel, "%.2f levels");
    ImGui::SliderFloat("gust size", &c.wind.gustSize, 1.0f, 50.0f, "%.1f m");
    ImGui::SliderFloat("gust speed", &c.wind.gustSpeed, 0.0f, 30.0f, "%.1f m/s");
}

void daySection(ViewControls& c) {
    float hours = float(c.hours);
    if (ImGui::SliderFloat("time of day", &hours, 0.0f, 24.0f, "%.2f h"))
        c.hours = double(hours);
    ImGui::Checkbox("play the day", &c.playDay);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120.0f);
    ImGui::SliderFloat("h per s", &c.daySpeed, 0.01f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
}

void viewSection(ViewControls& c, ViewRequests& r, FlyCamera& camera, const HudStats& s) {
    ImGui::Checkbox("LOD colours", &c.lodColours);
    ImGui::SameLine();
    ImGui::Checkbox("freeze culling", &c.freezeCulling);
    bool walk = camera.walk;
    if (ImGui::Checkbox("walk", &walk))
        r.toggleWalk = true;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(140.0f);
    ImGui::SliderFloat("speed", &camera.settings.speed, kMinFlySpeed, kMaxFlySpeed, "%.2f m/s",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::Text("eye %.2f %.2f %.2f  yaw %.0f  pitch %.0f", camera.eye.x, camera.eye.y, camera.eye.z,
                double(camera.yaw) * 57.29578, double(camera.pitch) * 57.29578);
    if (ImGui::Button("start view"))
        r.resetCamera = true;
    if (s.hasPath) {
        ImGui::SameLine();
        if (ImGui::Button(s.playing ? "stop path" : "play path"))
            r.togglePlayback = true;
        if (s.playing) {
            ImGui::SameLine();
            ImGui::Text("%.1f / %.1f s", s.pathTime, s.pathDuration);
        }
    }
    if (s.canRecord) {
        ImGui::SameLine();
        if (ImGui::Button(s.recording ? "stop recording" : "record path"))
            r.toggleRecording = true;
        if (s.recording) {
            ImGui::SameLine();
            ImGui::Text("%zu keys", s.recordedKeyframes);
        }
    }
    ImGui::Checkbox("vsync", &c.vsync);
    ImGui::SameLine();
    ImGui::Checkbox("fullscreen", &c.fullscreen);
    ImGui::SameLine();
    if (ImGui::Button("screenshot"))
        r.screenshot = true;
    if (!s.lastScreenshot.empty())
        ImGui::TextWrapped("last: %s", s.lastScreenshot.c_str());
}

void helpWindow(ViewControls& c) {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + vp->WorkSize.x - 10.0f, vp->WorkPos.y + 10.0f), ImGuiCond_Always,
                            ImVec2(1.0f, 0.0f));
    ImGui::SetNextWindowBgAlpha(0.8f);
    if (ImGui::Begin("keys and mouse", &c.showHelp,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings)) {
        if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_SizingFixedFit)) {
            for (const KeyBinding& b : keyBindings()) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(b.keys);
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(b.action);
            }
            ImGui::EndTable();
        }
    }
    ImGui::End();
}

} // namespace

void drawHudPanels(ViewControls& c, ViewRequests& r, FlyCamera& camera, const HudStats& s) {
    ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_FirstUseEver);
    // Fits its content: the sections open and close.
    if (ImGui::Begin("meadow (H: keys, F1: hide)", nullptr,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
        statsSection(s);
        if (ImGui::CollapsingHeader("wind"))
            windSection(c);
        if (ImGui::CollapsingHeader("time of day"))
            daySection(c);
        if (ImGui::CollapsingHeader("view", ImGuiTreeNodeFlags_DefaultOpen))
            viewSection(c, r, camera, s);
        if (s.scripted)
            ImGui::TextDisabled("scripted input: keys and mouse are ignored");
    }
    ImGui::End();
    if (c.showHelp)
        helpWindow(c);
}

} // namespace meadow
