// meadow view: the interactive walkthrough window (a free-flying or walking camera, a HUD with
// the cost of every pass and the wind and sky controls, camera paths, screenshots).
#include "app/commands.h"
#include "app/session.h"
#include "core/error.h"
#include "io/image_io.h"
#include "render/camera_path.h"
#include "render/field_renderer.h"
#include "render/window.h"
#include "ui/fly_camera.h"
#include "ui/hud.h"
#include "ui/hud_panels.h"
#include "ui/input_script.h"
#include "ui/view_controls.h"
#include "vk/timestamps.h"
#include "vk/vk_check.h"

#include <GLFW/glfw3.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>

namespace meadow {
namespace {

const char* kViewUsage = R"(usage: meadow view SCENE [options]

Opens the walkthrough: a window onto the field with a free-flying camera, a HUD that shows what
every pass costs (frames per second, GPU time per pass, visible instances per LOD, triangles)
and controls for the wind, the time of day and the debug views.

keys and mouse:
)";

const char* kViewOptions = R"(
options:
  --size WxH            initial window size (default 1280x720)
  --time-of-day H       local solar hour, 0-24 (default: the scene's)
  --wind L              base wind level, 0 (calm) to the scene's top level (default 1.2)
  --camera EX,EY,EZ,TX,TY,TZ   starting eye and target (default: the scene's, or the path's start)
  --camera-path FILE    a camera path (JSON keyframes) that P plays; the same file drives
                        meadow render and meadow bench --camera-path
  --play                start playing the --camera-path at once
  --record-path FILE    where R saves the path it records (default: a new file in --out-dir)
  --out-dir DIR         where F12 writes screenshots (and R paths): default the current folder
  --walk                start walking (eye 1.7 m above the ground) instead of flying
  --no-hud              start with the HUD hidden (F1 shows it)
  --no-vsync            start with vsync off (IMMEDIATE or MAILBOX presentation when offered)
  --fullscreen          start fullscreen
  --script FILE         scripted input: keys, mouse moves and window events frame by frame (the
                        format is below); the clocks then step 1/30 s per frame, and the real
                        keyboard and mouse are ignored
  --frames N            quit by itself after N frames
  --screenshot FILE     on exit, write the last frame shown (HUD included when shown) to FILE (.png)
  --preset, --seed, --device, --validation, --verbose   as for meadow render

script format, one event per line, "FRAME COMMAND [ARGS]" ('#' comments; events of frame F
happen before frame F is drawn; frames must not decrease):
  down KEY | up KEY | tap KEY      hold, release, or press once (W, F12, Escape, LeftShift, [ ...)
  mouse-down BUTTON | mouse-up BUTTON   left, right or middle
  move DX DY                       the cursor moves by (DX, DY) pixels
  scroll STEPS                     the mouse wheel
  resize W H                       the window's size becomes W x H
  minimize SECONDS                 minimise, and restore after SECONDS
  log                              print the camera and the controls (one 'meadow: state' line)
  quit                             end the walkthrough
)";

constexpr double kScriptStep = 1.0 / 30.0; // seconds per frame under --script
constexpr double kRecordInterval = 0.2;    // seconds between recorded keyframes
constexpr double kWarmUpSeconds = 2.0;     // motion played before the first frame, as render does

std::string timestampText() {
    std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char text[32];
    std::strftime(text, sizeof(text), "%Y%m%d-%H%M%S", &local);
    return text;
}

// Per-pass GPU times, frame times and counts averaged over about half a second, for the HUD.
struct StatsWindow {
    std::map<std::string, double> passSums;
    std::vector<std::string> passOrder;
    double wallSeconds = 0.0;
    uint32_t frames = 0;

    void add(const std::vector<PassTime>& passes, double wall) {
        for (const PassTime& p : passes) {
            if (!passSums.count(p.label))
                passOrder.push_back(p.label);
            passSums[p.label] += p.milliseconds;
        }
        wallSeconds += wall;
        ++frames;
    }
    // Publishes the averages into `stats` and starts again, once enough time has passed.
    bool publish(HudStats& stats, double minimumSeconds) {
        if (frames == 0 || wallSeconds < minimumSeconds)
            return false;
        stats.fps = double(frames) / wallSeconds;
        stats.cpuFrameMs = 1000.0 * wallSeconds / double(frames);
        stats.gpu.clear();
        stats.gpuTotalMs = 0.0;
        for (const std::string& label : passOrder) {
            double ms = passSums[label] / double(frames);
            stats.gpu.push_back({label, ms});
            stats.gpuTotalMs += ms;
        }
        *this = StatsWindow{};
        return true;
    }
};

// Keyframes of the camera while R is on, saved when it is switched off (or at exit).
struct PathRecorder {
    std::filesystem::path file;
    bool recording = false;
    double time = 0.0;
    CameraPath path;

    // Key times to the microsecond: the file reads 0.2, not 0.19999999999999998.
    double roundedTime() const { return std::round(time * 1e6) / 1e6; }

    void start(const CameraPose& pose) {
        recording = true;
        time = 0.0;
        path.keyframes = {{0.0, pose.eye, pose.target}};
        std::fprintf(stderr, "meadow: recording a camera path (R again stops and saves it)\n");
    }
    void step(double dt, const CameraPose& pose) {
        time += dt;
        if (time - path.keyframes.back().time >= kRecordInterval - 1e-9)
            path.keyframes.push_back({roundedTime(), pose.eye, pose.target});
    }
    // Returns false when the file could not be written (the message is printed).
    bool stop(const CameraPose& pose) {
        recording = false;
        if (roundedTime() > path.keyframes.back().time)
            path.keyframes.push_back({roundedTime(), pose.eye, pose.target});
        try {
            saveCameraPath(file, path);
        } catch (const Error& e) {
            std::fprintf(stderr, "meadow: error: %s\n", e.what());
            return false;
        }
        std::fprintf(stderr, "meadow: camera path of %zu keyframes (%.2f s) saved to %s\n", path.keyframes.size(),
                     path.duration(), file.string().c_str());
        return true;
    }
};

struct ViewOptions {
    uint32_t width = 1280, height = 720;
    uint32_t maxFrames = 0;
    std::optional<InputScript> script;
    std::optional<CameraPath> path;
    std::optional<std::filesystem::path> screenshotOnExit;
    std::filesystem::path outDir = ".";
    std::filesystem::path recordFile;
};

void printState(uint32_t frame, const FlyCamera& fly, const GroundHeight& ground, const ViewControls& c,
                const Window& window, bool playing) {
    std::optional<float> h = ground.at(fly.eye.x, fly.eye.z);
    std::fprintf(stderr,
                 "meadow: state frame=%u eye=%.4f,%.4f,%.4f yaw=%.5f pitch=%.5f ground=%.4f walk=%d speed=%.3f "
                 "wind=%.3f hours=%.3f lod=%d freeze=%d vsync=%d fullscreen=%d window=%ux%u playing=%d\n",
                 frame, fly.eye.x, fly.eye.y, fly.eye.z, fly.yaw, fly.pitch, h ? *h : std::nanf(""), int(fly.walk),
                 fly.settings.speed, c.wind.baseLevel, c.hours, int(c.lodColours), int(c.freezeCulling),
                 int(window.vsync), int(window.fullscreen), window.extent.width, window.extent.height, int(playing));
}

ParsedArgs parseViewArgs(const Args& argv) {
    CommandSpec spec{"view",
                     {"SCENE"},
                     {"--size", "--time-of-day", "--wind", "--camera", "--camera-path", "--record-path", "--out-dir",
                      "--script", "--frames", "--screenshot"},
                     {"--no-vsync", "--fullscreen", "--walk", "--no-hud", "--play"}};
    addSceneOptions(spec);
    addEngineOptions(spec);
    addFieldOptions(spec);
    return parseArgs(spec, argv);
}

// The options checked before the scene loads, in the order their messages come (the record file
// is named once the scene is known: recordFileFromArgs).
ViewOptions viewOptionsFromArgs(const ParsedArgs& args) {
    ViewOptions opt;
    std::tie(opt.width, opt.height) = args.size("--size", {1280, 720});
    opt.maxFrames = args.u32("--frames", 0, 1, 100'000'000);
    if (auto s = args.value("--screenshot")) {
        if (imageKindForPath(*s) != ImageFileKind::Png)
            throw Error("meadow view: --screenshot " + *s + ": screenshots are PNG");
        checkOutputWritable(*s);
        opt.screenshotOnExit = *s;
    }
    if (auto d = args.value("--out-dir")) {
        std::error_code ec;
        if (!std::filesystem::is_directory(*d, ec))
            throw Error("meadow view: --out-dir " + *d + ": no such folder");
        opt.outDir = *d;
    }
    checkOutputWritable(opt.outDir / "meadow-screenshot.png");
    if (auto p = args.value("--camera-path"))
        opt.path = loadCameraPath(*p);
    if (args.has("--play") && !opt.path)
        throw Error("meadow view: --play needs --camera-path FILE");
    if (auto s = args.value("--script"))
        opt.script = loadInputScript(*s);
    return opt;
}

// Where R saves the path it records: --record-path, else a new file in the --out-dir.
std::filesystem::path recordFileFromArgs(const ParsedArgs& args, const std::filesystem::path& outDir,
                                         const Scene& scene) {
    std::filesystem::path recordFile;
    if (auto r = args.value("--record-path")) {
        recordFile = *r;
        checkOutputWritable(recordFile);
    } else {
        recordFile = outDir / ("meadow-" + scene.name + "-" + timestampText() + ".path.json");
    }
    return recordFile;
}

ViewControls viewControlsFromArgs(const ParsedArgs& args, const Scene& scene) {
    ViewControls controls;
    controls.topWindLevel = float(scene.wind.levelSpeeds.size() - 1);
    controls.hours = args.f32("--time-of-day", scene.timeOfDay, 0.0f, 24.0f);
    controls.wind.baseLevel =
        args.f32("--wind", std::min(controls.wind.baseLevel, controls.topWindLevel), 0.0f, controls.topWindLevel);
    controls.vsync = !args.has("--no-vsync");
    controls.fullscreen = args.has("--fullscreen");
    controls.showHud = !args.has("--no-hud");
    return controls;
}

// Where the camera starts (and goes back to on reset): --camera or the scene's camera, else the
// start of the --camera-path.
CameraPose startPoseFromArgs(const ParsedArgs& args, const ViewOptions& opt, const Camera& baseCamera) {
    CameraPose startPose{baseCamera.eye, baseCamera.target};
    if (opt.path && !args.has("--camera"))
        startPose = sampleCameraPath(*opt.path, opt.path->startTime());
    return startPose;
}

ContextOptions windowContextOptions(const ParsedArgs& args) {
    ContextOptions options = contextOptionsFromArgs(args);
    options.instanceExtensions = windowInstanceExtensions();
    options.presentation = true;
    options.presentSupport = windowPresentSupport;
    return options;
}

// The walkthrough: what was settled before its window opened (the references), the window and
// what draws into it, and the state carried from frame to frame.
struct Walkthrough {
    Context& ctx;
    ViewOptions& opt; // the script moves into `player`
    const Scene& scene;
    const Camera& baseCamera;
    const CameraPose& startPose;
    const GroundHeight& ground;
    ViewControls& controls;
    FlyCamera& fly;

    FieldRenderer renderer;
    InputState input; // GLFW's callbacks hold its address: a Walkthrough never moves
    std::optional<ScriptPlayer> player;
    Window window;
    Hud hud;
    GpuTimer timer;
    RenderTargets targets{};
    FrameState state;
    double sceneSeconds = 0.0;

    HudStats hudStats;
    StatsWindow statsWindow, logWindow;
    PathRecorder recorder;
    bool playing = false;
    double pathTime = 0.0;
    bool leftDragOwned = false; // a left drag that began off the HUD looks around
    bool quit = false, screenshotPending = false, timerHasFrame = false;
    uint32_t frame = 0, generation = 0;
    bool paused = false;
    bool restorePending = false; // a scripted minimise waits to restore the window at restoreAt
    std::chrono::steady_clock::time_point restoreAt, last;
    int failures = 0; // files that could not be written
};

// Creates the renderer, the window, the HUD and the GPU timer, and plays the warm-up motion.
void openWalkthrough(Walkthrough& w, const Library& library, const std::vector<FieldClump>& clumps,
                     const FieldScenery& scenery, bool play) {
    w.renderer = createFieldRenderer(w.ctx, clumps, fieldInstances(library), library.atlas, scenery);
    w.input.ignoreDevices = w.opt.script.has_value();
    if (w.opt.script)
        w.player.emplace(std::move(*w.opt.script));
    w.window = createWindow(w.ctx, "meadow — " + w.scene.name, w.opt.width, w.opt.height);
    attachInput(w.window.window, w.input); // before the HUD, whose GLFW backend chains onto it
    w.window.vsync = w.controls.vsync;
    w.hud = createHud(w.ctx, w.window);
    w.timer = createGpuTimer(w.ctx, 16);

    w.state.camera = w.baseCamera;
    w.state.width = w.opt.width; // until the swapchain says otherwise
    w.state.height = w.opt.height;
    applyControls(w.controls, w.state);
    w.state.seconds = kWarmUpSeconds;
    advanceMotion(w.ctx, w.renderer, w.state);
    w.sceneSeconds = kWarmUpSeconds;

    w.hudStats.device = w.ctx.deviceName();
    w.hudStats.hasPath = w.opt.path.has_value();
    w.hudStats.canRecord = true;
    w.hudStats.farRadius = w.renderer.farField ? w.renderer.lodParams.farRadius : 0.0f;
    w.hudStats.scripted = w.player.has_value();
    w.recorder.file = w.opt.recordFile;
    w.playing = play;
    w.restoreAt = std::chrono::steady_clock::now();
    w.last = std::chrono::steady_clock::now();
    if (w.playing)
        std::fprintf(stderr, "meadow: playing the camera path (%.2f s)\n", w.opt.path->duration());
}

// A scripted minimise: the window is iconified now and restored after e.seconds.
void minimiseForScript(Walkthrough& w, const ScriptEvent& e) {
    glfwIconifyWindow(w.window.window);
    // The window manager acts asynchronously; give it up to two seconds.
    auto asked = std::chrono::steady_clock::now();
    while (!glfwGetWindowAttrib(w.window.window, GLFW_ICONIFIED) &&
           std::chrono::steady_clock::now() - asked < std::chrono::seconds(2))
        glfwWaitEventsTimeout(0.05);
    if (!glfwGetWindowAttrib(w.window.window, GLFW_ICONIFIED))
        std::fprintf(stderr, "meadow: script: the window manager did not minimise the window\n");
    w.restorePending = true;
    w.restoreAt = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                         std::chrono::duration<double>(e.seconds));
}

// The script's window events for this frame (its keys and mouse go into the input). Returns
// whether one asks to log the state after the frame.
bool applyScriptEvents(Walkthrough& w) {
    bool logThisFrame = false;
    if (w.player)
        for (const ScriptEvent& e : w.player->advance(w.frame, w.input)) {
            using Kind = ScriptEvent::Kind;
            if (e.kind == Kind::Resize) {
                std::fprintf(stderr, "meadow: script: resize to %ux%u\n", e.width, e.height);
                glfwSetWindowSize(w.window.window, int(e.width), int(e.height));
            } else if (e.kind == Kind::Minimize) {
                minimiseForScript(w, e);
            } else if (e.kind == Kind::Log) {
                logThisFrame = true;
            } else if (e.kind == Kind::Quit) {
                w.quit = true;
            }
        }
    return logThisFrame;
}

// Window changes asked for last frame (keys or HUD), before an image is acquired.
void applyWindowChanges(Walkthrough& w) {
    if (w.controls.fullscreen != w.window.fullscreen) {
        setFullscreen(w.window, w.controls.fullscreen);
        w.controls.fullscreen = w.window.fullscreen;
        std::fprintf(stderr, "meadow: fullscreen %s\n", w.window.fullscreen ? "on" : "off");
    }
    if (w.controls.vsync != w.window.vsync) {
        setVsync(w.ctx, w.window, w.controls.vsync);
        std::fprintf(stderr, "meadow: vsync %s\n", w.window.vsync ? "on" : "off");
    }
}

// Minimised (iconified, or a zero-sized framebuffer on platforms that shrink it): nothing is
// visible, so render nothing and wait for the window to come back. Returns whether it is.
bool waitWhileMinimised(Walkthrough& w, VkExtent2D fb) {
    if (fb.width == 0 || fb.height == 0 || glfwGetWindowAttrib(w.window.window, GLFW_ICONIFIED)) {
        if (!w.paused) {
            std::fprintf(stderr, "meadow: window minimised; rendering paused\n");
            w.paused = true;
        }
        if (w.restorePending && std::chrono::steady_clock::now() >= w.restoreAt) {
            glfwRestoreWindow(w.window.window);
            w.restorePending = false;
        }
        glfwWaitEventsTimeout(0.05);
        return true;
    }
    if (w.paused) {
        std::fprintf(stderr, "meadow: window restored; rendering resumed\n");
        w.paused = false;
        w.last = std::chrono::steady_clock::now();
    }
    return false;
}

// A swapchain at the framebuffer's size, and render targets at the swapchain's. Returns false
// when the swapchain cannot be made now (the frame is skipped).
bool prepareSwapchain(Walkthrough& w, VkExtent2D fb) {
    if (w.window.swapchain == VK_NULL_HANDLE || w.window.recreateNeeded || fb.width != w.window.extent.width ||
        fb.height != w.window.extent.height) {
        if (!recreateSwapchain(w.ctx, w.window))
            return false;
    }
    if (w.generation != w.window.swapchainGeneration) {
        // Render at the window's size so the copy into the composite is 1:1.
        VK_CHECK(vkDeviceWaitIdle(w.ctx.device));
        destroyRenderTargets(w.ctx, w.targets);
        // The window shows the LDR image: the HDR image need not hold the far field.
        w.targets = createRenderTargets(w.ctx, w.window.extent, HdrContents::MeshPass);
        w.generation = w.window.swapchainGeneration;
        std::fprintf(stderr, "meadow: window %ux%u, present mode %s\n", w.window.extent.width, w.window.extent.height,
                     presentModeName(w.window.presentMode));
    }
    return true;
}

// Seconds since the last frame began (wall clock); this frame begins now.
double secondsSinceLastFrame(Walkthrough& w) {
    auto now = std::chrono::steady_clock::now();
    const double wall = std::chrono::duration<double>(now - w.last).count();
    w.last = now;
    return wall;
}

// The last frame's GPU times and counts: into the HUD's averages, and every two seconds a log line.
void readFrameStats(Walkthrough& w, double wall) {
    std::vector<PassTime> passes = readTimestamps(w.ctx, w.timer);
    FieldStats fieldStats = readFieldStats(w.renderer);
    w.hudStats.visibleInstances = fieldStats.visibleInstances;
    w.hudStats.testedInstances = fieldStats.testedInstances;
    w.hudStats.triangles = fieldStats.trianglesDrawn;
    w.hudStats.nearRaster = w.renderer.nearRasterOn;
    w.hudStats.nearDraws = fieldStats.nearInstances;
    w.hudStats.nearTriangles = fieldStats.nearTriangles;
    w.hudStats.farInstances = fieldStats.farInstances;
    w.hudStats.farSamples = fieldStats.farSamples;
    w.hudStats.instancesPerLod = fieldStats.drawsPerLod();
    w.statsWindow.add(passes, wall);
    w.logWindow.add(passes, wall);
    w.statsWindow.publish(w.hudStats, 0.5);
    HudStats logged;
    if (w.logWindow.publish(logged, 2.0)) {
        std::string perPass;
        for (const PassTime& p : logged.gpu)
            perPass += " " + p.label + " " + std::to_string(p.milliseconds).substr(0, 5);
        std::fprintf(stderr, "meadow: %.1f fps, GPU %.2f ms (%s ), %u of %u instances visible, %u in the far field\n",
                     logged.fps, logged.gpuTotalMs, perPass.c_str(), fieldStats.visibleInstances,
                     fieldStats.testedInstances, fieldStats.farInstances);
    }
}

// The requests of the keys and of the HUD, which is drawn now when shown.
ViewRequests shortcutsAndHud(Walkthrough& w, const InputFrame& in, bool hudKeyboard) {
    ViewRequests requests = applyShortcuts(in, hudKeyboard, w.controls);
    w.hudStats.width = w.window.extent.width;
    w.hudStats.height = w.window.extent.height;
    w.hudStats.presentMode = presentModeName(w.window.presentMode);
    w.hudStats.playing = w.playing;
    w.hudStats.pathTime = w.pathTime;
    w.hudStats.pathDuration = w.opt.path ? w.opt.path->duration() : 0.0;
    w.hudStats.recording = w.recorder.recording;
    w.hudStats.recordedKeyframes = w.recorder.path.keyframes.size();
    if (w.controls.showHud)
        drawHudPanels(w.controls, requests, w.fly, w.hudStats);
    if (w.controls.showHelp && !w.controls.showHud)
        w.controls.showHud = true; // H asks for the help, which is part of the HUD
    return requests;
}

void applyRequests(Walkthrough& w, const ViewRequests& requests) {
    if (requests.quit)
        w.quit = true; // after this frame
    if (requests.toggleWalk) {
        w.fly.walk = !w.fly.walk;
        w.fly.settle(&w.ground);
        std::fprintf(stderr, "meadow: %s\n", w.fly.walk ? "walking" : "flying");
    }
    if (requests.resetCamera) {
        w.fly.setPose(w.startPose);
        w.fly.settle(&w.ground);
        w.playing = false;
    }
    if (requests.togglePlayback) {
        if (!w.opt.path) {
            std::fprintf(stderr, "meadow: no camera path to play (start with --camera-path FILE)\n");
        } else {
            w.playing = !w.playing;
            w.pathTime = 0.0;
            std::fprintf(stderr, "meadow: camera path %s\n", w.playing ? "playing" : "stopped");
        }
    }
    if (requests.toggleRecording) {
        if (w.recorder.recording)
            w.failures += w.recorder.stop(w.fly.pose()) ? 0 : 1;
        else
            w.recorder.start(w.fly.pose());
    }
    w.screenshotPending = w.screenshotPending || requests.screenshot;
}

// The camera: the path while it plays, else the keys and the mouse; and the recording of it.
void moveCamera(Walkthrough& w, const InputFrame& in, bool hudMouse, bool hudKeyboard, double dt) {
    if (in.mousePressed[size_t(MouseButton::Left)])
        w.leftDragOwned = !hudMouse;
    if (!in.button(MouseButton::Left))
        w.leftDragOwned = false;
    const bool looking = in.button(MouseButton::Right) || (in.button(MouseButton::Left) && w.leftDragOwned);
    if (w.playing) {
        w.pathTime += dt;
        w.fly.setPose(sampleCameraPath(*w.opt.path, w.opt.path->startTime() + w.pathTime));
        if (w.pathTime >= w.opt.path->duration()) {
            w.playing = false;
            std::fprintf(stderr, "meadow: camera path finished\n");
        }
    } else {
        w.fly.update(in, looking, !hudKeyboard, float(dt), &w.ground);
    }
    if (w.recorder.recording)
        w.recorder.step(dt, w.fly.pose());
}

// The day and the scene's clock move on; the renderer gets the frame's camera and controls.
void advanceScene(Walkthrough& w, double dt) {
    advanceDay(w.controls, dt);
    w.sceneSeconds += dt;
    const CameraPose pose = w.fly.pose();
    w.state.camera = w.baseCamera;
    w.state.camera.eye = pose.eye;
    w.state.camera.target = pose.target;
    w.state.width = w.targets.extent.width;
    w.state.height = w.targets.extent.height;
    w.state.seconds = w.sceneSeconds;
    applyControls(w.controls, w.state);
    updateFrame(w.ctx, w.renderer, w.state);
}

void recordAndPresent(Walkthrough& w, uint32_t imageIndex) {
    VK_CHECK(vkResetCommandBuffer(w.window.cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(w.window.cmd, &begin));
    recordFieldFrame(w.ctx, w.renderer, w.window.cmd, w.targets, &w.timer);
    recordFrameToComposite(w.window.cmd, w.window, w.targets);
    recordHud(w.ctx, w.hud, w.window.cmd, w.window, w.controls.showHud);
    recordCompositeToSwapchain(w.window.cmd, w.window, imageIndex, access::kColorAttachmentWrite);
    markTimestamp(w.timer, w.window.cmd, "window"); // copy, HUD and blit to the swapchain
    VK_CHECK(vkEndCommandBuffer(w.window.cmd));
    submitAndPresent(w.ctx, w.window, imageIndex);
    w.timerHasFrame = true;
}

// F12: the frame just shown, to a new file in the --out-dir.
void writePendingScreenshot(Walkthrough& w) {
    if (!w.screenshotPending || !w.window.compositeHasFrame)
        return;
    w.screenshotPending = false;
    std::filesystem::path file =
        w.opt.outDir / ("meadow-" + w.scene.name + "-" + timestampText() + "-f" + std::to_string(w.frame - 1) + ".png");
    try {
        VK_CHECK(vkWaitForFences(w.ctx.device, 1, &w.window.frameFence, VK_TRUE, UINT64_MAX));
        writeRgba8(file, w.window.composite.extent.width, w.window.composite.extent.height,
                   readCompositePixels(w.ctx, w.window));
        w.hudStats.lastScreenshot = file.string();
        std::fprintf(stderr, "meadow: screenshot %ux%u written to %s\n", w.window.composite.extent.width,
                     w.window.composite.extent.height, file.string().c_str());
    } catch (const Error& e) {
        std::fprintf(stderr, "meadow: error: %s\n", e.what());
        ++w.failures;
    }
}

// One frame, once an image is acquired: input, HUD, requests, camera, scene, record and present.
void drawFrame(Walkthrough& w, double wall, uint32_t imageIndex, bool logThisFrame) {
    const double dt = w.player ? kScriptStep : std::min(wall, 0.1);
    const InputFrame in = w.input.takeFrame();
    beginHudFrame(w.window);
    const bool hudMouse = hudWantsMouse();
    const bool hudKeyboard = hudWantsKeyboard();
    const ViewRequests requests = shortcutsAndHud(w, in, hudKeyboard);
    applyRequests(w, requests);
    moveCamera(w, in, hudMouse, hudKeyboard, dt);
    advanceScene(w, dt);
    recordAndPresent(w, imageIndex);
    if (logThisFrame)
        printState(w.frame, w.fly, w.ground, w.controls, w.window, w.playing);
    ++w.frame;
    writePendingScreenshot(w);
}

// Frames until a quit (Escape, the HUD, the script), --frames, or the window is closed.
void runFrames(Walkthrough& w) {
    while (!w.quit && !glfwWindowShouldClose(w.window.window)) {
        glfwPollEvents();
        if (w.opt.maxFrames && w.frame >= w.opt.maxFrames)
            break;
        const bool logThisFrame = applyScriptEvents(w);
        if (w.quit)
            break;
        applyWindowChanges(w);
        const VkExtent2D fb = framebufferExtent(w.window);
        if (waitWhileMinimised(w, fb) || !prepareSwapchain(w, fb))
            continue;
        VK_CHECK(vkWaitForFences(w.ctx.device, 1, &w.window.frameFence, VK_TRUE, UINT64_MAX));
        const double wall = secondsSinceLastFrame(w);
        if (w.timerHasFrame)
            readFrameStats(w, wall);
        uint32_t imageIndex = 0;
        if (!acquireImage(w.ctx, w.window, imageIndex))
            continue;
        VK_CHECK(vkResetFences(w.ctx.device, 1, &w.window.frameFence));
        drawFrame(w, wall, imageIndex, logThisFrame);
    }
}

// After the last frame: the recording saved, the --screenshot written, a summary printed.
void finishWalkthrough(Walkthrough& w) {
    VK_CHECK(vkDeviceWaitIdle(w.ctx.device));
    if (w.recorder.recording)
        w.failures += w.recorder.stop(w.fly.pose()) ? 0 : 1;
    if (w.player && !w.player->finished() && !w.quit)
        std::fprintf(stderr, "meadow: the window closed before the script ended\n");
    if (w.opt.screenshotOnExit) {
        if (w.frame == 0 || !w.window.compositeHasFrame)
            throw Error("meadow view: no frame is on screen, so there is no screenshot to write");
        writeRgba8(*w.opt.screenshotOnExit, w.window.composite.extent.width, w.window.composite.extent.height,
                   readCompositePixels(w.ctx, w.window));
        std::fprintf(stderr, "meadow: screenshot %ux%u written to %s\n", w.window.composite.extent.width,
                     w.window.composite.extent.height, w.opt.screenshotOnExit->string().c_str());
    }
    std::fprintf(stderr, "meadow: view showed %u frames; window %ux%u at exit\n", w.frame, w.window.extent.width,
                 w.window.extent.height);
}

void closeWalkthrough(Walkthrough& w) {
    destroyHud(w.ctx, w.hud);
    destroyGpuTimer(w.ctx, w.timer);
    destroyRenderTargets(w.ctx, w.targets);
    destroyWindow(w.ctx, w.window);
    destroyFieldRenderer(w.ctx, w.renderer);
}

// The validation layer's status, else 1 when a file could not be written.
int exitStatus(int validationStatus, int failures) {
    if (failures > 0) {
        std::fprintf(stderr, "meadow: %d file%s could not be written (see above)\n", failures,
                     failures == 1 ? "" : "s");
        return validationStatus != 0 ? validationStatus : 1;
    }
    return validationStatus;
}

} // namespace

int runView(const Args& argv) {
    const std::string help = std::string(kViewUsage) + keyHelpText() + kViewOptions + kFieldOptionsHelp;
    if (printHelpIfAsked(argv, help.c_str()))
        return 0;
    ParsedArgs args = parseViewArgs(argv);

    // Everything the command line names is checked before a window opens.
    ViewOptions opt = viewOptionsFromArgs(args);
    const FieldOptions fieldOptions = fieldOptionsFromArgs(args);
    Scene scene = sceneFromArgs(args);
    opt.recordFile = recordFileFromArgs(args, opt.outDir, scene);
    ViewControls controls = viewControlsFromArgs(args, scene);
    Camera baseCamera = cameraFromArgs(args, scene);
    CameraPose startPose = startPoseFromArgs(args, opt, baseCamera);

    initWindowSystem(); // no display: say so before the library loads
    Library library = ensureLibrary(scene);
    FieldScenery scenery = fieldScenery(library, fieldOptions.lodTolerance);
    std::vector<FieldClump> clumps = fieldClumps(library);
    applyFieldOptions(fieldOptions, clumps, scenery);
    const GroundHeight ground(scenery.terrain);
    FlyCamera fly(startPose);
    fly.walk = args.has("--walk");
    fly.settle(&ground);

    Context ctx;
    createContext(ctx, windowContextOptions(args));
    int failures = 0;
    {
        Walkthrough w{.ctx = ctx,
                      .opt = opt,
                      .scene = scene,
                      .baseCamera = baseCamera,
                      .startPose = startPose,
                      .ground = ground,
                      .controls = controls,
                      .fly = fly};
        openWalkthrough(w, library, clumps, scenery, args.has("--play"));
        runFrames(w);
        finishWalkthrough(w);
        closeWalkthrough(w);
        failures = w.failures;
    }
    int status = validationExitStatus(ctx);
    destroyContext(ctx);
    terminateWindowSystem();
    return exitStatus(status, failures);
}

} // namespace meadow
