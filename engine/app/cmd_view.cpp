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

} // namespace

int runView(const Args& argv) {
    const std::string help = std::string(kViewUsage) + keyHelpText() + kViewOptions;
    if (printHelpIfAsked(argv, help.c_str()))
        return 0;
    CommandSpec spec{"view",
                     {"SCENE"},
                     {"--size", "--time-of-day", "--wind", "--camera", "--camera-path", "--record-path", "--out-dir",
                      "--script", "--frames", "--screenshot"},
                     {"--no-vsync", "--fullscreen", "--walk", "--no-hud", "--play"}};
    addSceneOptions(spec);
    addEngineOptions(spec);
    ParsedArgs args = parseArgs(spec, argv);

    // Everything the command line names is checked before a window opens.
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
    Scene scene = sceneFromArgs(args);
    if (auto r = args.value("--record-path")) {
        opt.recordFile = *r;
        checkOutputWritable(opt.recordFile);
    } else {
        opt.recordFile = opt.outDir / ("meadow-" + scene.name + "-" + timestampText() + ".path.json");
    }

    ViewControls controls;
    controls.topWindLevel = float(scene.wind.levelSpeeds.size() - 1);
    controls.hours = args.f32("--time-of-day", scene.timeOfDay, 0.0f, 24.0f);
    controls.wind.baseLevel =
        args.f32("--wind", std::min(controls.wind.baseLevel, controls.topWindLevel), 0.0f, controls.topWindLevel);
    controls.vsync = !args.has("--no-vsync");
    controls.fullscreen = args.has("--fullscreen");
    controls.showHud = !args.has("--no-hud");
    Camera baseCamera = cameraFromArgs(args, scene);
    CameraPose startPose{baseCamera.eye, baseCamera.target};
    if (opt.path && !args.has("--camera"))
        startPose = sampleCameraPath(*opt.path, opt.path->startTime());

    initWindowSystem(); // no display: say so before the library loads
    Library library = ensureLibrary(scene);
    FieldScenery scenery = fieldScenery(library);
    const GroundHeight ground(scenery.terrain);
    FlyCamera fly(startPose);
    fly.walk = args.has("--walk");
    fly.settle(&ground);

    ContextOptions options = contextOptionsFromArgs(args);
    options.instanceExtensions = windowInstanceExtensions();
    options.presentation = true;
    options.presentSupport = windowPresentSupport;
    Context ctx;
    createContext(ctx, options);
    int failures = 0;
    {
        FieldRenderer renderer =
            createFieldRenderer(ctx, fieldClumps(library), fieldInstances(library), library.atlas, scenery);
        InputState input;
        input.ignoreDevices = opt.script.has_value();
        std::optional<ScriptPlayer> player;
        if (opt.script)
            player.emplace(std::move(*opt.script));
        Window window = createWindow(ctx, "meadow — " + scene.name, opt.width, opt.height);
        attachInput(window.window, input); // before the HUD, whose GLFW backend chains onto it
        window.vsync = controls.vsync;
        Hud hud = createHud(ctx, window);
        GpuTimer timer = createGpuTimer(ctx, 16);
        RenderTargets targets{};

        FrameState state;
        state.camera = baseCamera;
        state.width = opt.width; // until the swapchain says otherwise
        state.height = opt.height;
        applyControls(controls, state);
        state.seconds = kWarmUpSeconds;
        advanceMotion(ctx, renderer, state);
        double sceneSeconds = kWarmUpSeconds;

        HudStats hudStats;
        hudStats.device = ctx.deviceName();
        hudStats.hasPath = opt.path.has_value();
        hudStats.canRecord = true;
        hudStats.scripted = player.has_value();
        StatsWindow statsWindow, logWindow;
        PathRecorder recorder{opt.recordFile};
        bool playing = args.has("--play");
        double pathTime = 0.0;
        bool leftDragOwned = false; // a left drag that began off the HUD looks around
        bool quit = false, screenshotPending = false, timerHasFrame = false;
        uint32_t frame = 0, generation = 0;
        bool paused = false;
        bool restorePending = false; // a scripted minimise waits to restore the window at restoreAt
        auto restoreAt = std::chrono::steady_clock::now();
        auto last = std::chrono::steady_clock::now();
        if (playing)
            std::fprintf(stderr, "meadow: playing the camera path (%.2f s)\n", opt.path->duration());

        while (!quit && !glfwWindowShouldClose(window.window)) {
            glfwPollEvents();
            if (opt.maxFrames && frame >= opt.maxFrames)
                break;
            bool logThisFrame = false;
            if (player)
                for (const ScriptEvent& e : player->advance(frame, input)) {
                    using Kind = ScriptEvent::Kind;
                    if (e.kind == Kind::Resize) {
                        std::fprintf(stderr, "meadow: script: resize to %ux%u\n", e.width, e.height);
                        glfwSetWindowSize(window.window, int(e.width), int(e.height));
                    } else if (e.kind == Kind::Minimize) {
                        glfwIconifyWindow(window.window);
                        // The window manager acts asynchronously; give it up to two seconds.
                        auto asked = std::chrono::steady_clock::now();
                        while (!glfwGetWindowAttrib(window.window, GLFW_ICONIFIED) &&
                               std::chrono::steady_clock::now() - asked < std::chrono::seconds(2))
                            glfwWaitEventsTimeout(0.05);
                        if (!glfwGetWindowAttrib(window.window, GLFW_ICONIFIED))
                            std::fprintf(stderr, "meadow: script: the window manager did not minimise the window\n");
                        restorePending = true;
                        restoreAt = std::chrono::steady_clock::now() +
                                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                        std::chrono::duration<double>(e.seconds));
                    } else if (e.kind == Kind::Log) {
                        logThisFrame = true;
                    } else if (e.kind == Kind::Quit) {
                        quit = true;
                    }
                }
            if (quit)
                break;

            // Window changes asked for last frame (keys or HUD), before an image is acquired.
            if (controls.fullscreen != window.fullscreen) {
                setFullscreen(window, controls.fullscreen);
                controls.fullscreen = window.fullscreen;
                std::fprintf(stderr, "meadow: fullscreen %s\n", window.fullscreen ? "on" : "off");
            }
            if (controls.vsync != window.vsync) {
                setVsync(ctx, window, controls.vsync);
                std::fprintf(stderr, "meadow: vsync %s\n", window.vsync ? "on" : "off");
            }

            // Minimised (iconified, or a zero-sized framebuffer on platforms that shrink it):
            // nothing is visible, so render nothing and wait for the window to come back.
            VkExtent2D fb = framebufferExtent(window);
            if (fb.width == 0 || fb.height == 0 || glfwGetWindowAttrib(window.window, GLFW_ICONIFIED)) {
                if (!paused) {
                    std::fprintf(stderr, "meadow: window minimised; rendering paused\n");
                    paused = true;
                }
                if (restorePending && std::chrono::steady_clock::now() >= restoreAt) {
                    glfwRestoreWindow(window.window);
                    restorePending = false;
                }
                glfwWaitEventsTimeout(0.05);
                continue;
            }
            if (paused) {
                std::fprintf(stderr, "meadow: window restored; rendering resumed\n");
                paused = false;
                last = std::chrono::steady_clock::now();
            }
            if (window.swapchain == VK_NULL_HANDLE || window.recreateNeeded || fb.width != window.extent.width ||
                fb.height != window.extent.height) {
                if (!recreateSwapchain(ctx, window))
                    continue;
            }
            if (generation != window.swapchainGeneration) {
                // Render at the window's size so the copy into the composite is 1:1.
                VK_CHECK(vkDeviceWaitIdle(ctx.device));
                destroyRenderTargets(ctx, targets);
                targets = createRenderTargets(ctx, window.extent);
                generation = window.swapchainGeneration;
                std::fprintf(stderr, "meadow: window %ux%u, present mode %s\n", window.extent.width,
                             window.extent.height, presentModeName(window.presentMode));
            }

            VK_CHECK(vkWaitForFences(ctx.device, 1, &window.frameFence, VK_TRUE, UINT64_MAX));
            auto now = std::chrono::steady_clock::now();
            const double wall = std::chrono::duration<double>(now - last).count();
            last = now;
            if (timerHasFrame) {
                std::vector<PassTime> passes = readTimestamps(ctx, timer);
                FieldStats fieldStats = readFieldStats(renderer);
                hudStats.visibleInstances = fieldStats.visibleInstances;
                hudStats.testedInstances = fieldStats.testedInstances;
                hudStats.triangles = fieldStats.trianglesDrawn;
                hudStats.instancesPerLod.assign(renderer.lodCount, 0);
                for (size_t m = 0; m < fieldStats.visiblePerMesh.size(); ++m)
                    hudStats.instancesPerLod[m % renderer.lodCount] += fieldStats.visiblePerMesh[m];
                statsWindow.add(passes, wall);
                logWindow.add(passes, wall);
                statsWindow.publish(hudStats, 0.5);
                HudStats logged;
                if (logWindow.publish(logged, 2.0)) {
                    std::string perPass;
                    for (const PassTime& p : logged.gpu)
                        perPass += " " + p.label + " " + std::to_string(p.milliseconds).substr(0, 5);
                    std::fprintf(stderr, "meadow: %.1f fps, GPU %.2f ms (%s ), %u of %u instances visible\n",
                                 logged.fps, logged.gpuTotalMs, perPass.c_str(), fieldStats.visibleInstances,
                                 fieldStats.testedInstances);
                }
            }
            uint32_t imageIndex = 0;
            if (!acquireImage(ctx, window, imageIndex))
                continue;
            VK_CHECK(vkResetFences(ctx.device, 1, &window.frameFence));

            // This frame's input, the HUD and the requests of both.
            const double dt = player ? kScriptStep : std::min(wall, 0.1);
            const InputFrame in = input.takeFrame();
            beginHudFrame(window);
            const bool hudMouse = hudWantsMouse();
            const bool hudKeyboard = hudWantsKeyboard();
            ViewRequests requests = applyShortcuts(in, hudKeyboard, controls);
            hudStats.width = window.extent.width;
            hudStats.height = window.extent.height;
            hudStats.presentMode = presentModeName(window.presentMode);
            hudStats.playing = playing;
            hudStats.pathTime = pathTime;
            hudStats.pathDuration = opt.path ? opt.path->duration() : 0.0;
            hudStats.recording = recorder.recording;
            hudStats.recordedKeyframes = recorder.path.keyframes.size();
            if (controls.showHud)
                drawHudPanels(controls, requests, fly, hudStats);
            if (controls.showHelp && !controls.showHud)
                controls.showHud = true; // H asks for the help, which is part of the HUD

            if (requests.quit)
                quit = true; // after this frame
            if (requests.toggleWalk) {
                fly.walk = !fly.walk;
                fly.settle(&ground);
                std::fprintf(stderr, "meadow: %s\n", fly.walk ? "walking" : "flying");
            }
            if (requests.resetCamera) {
                fly.setPose(startPose);
                fly.settle(&ground);
                playing = false;
            }
            if (requests.togglePlayback) {
                if (!opt.path) {
                    std::fprintf(stderr, "meadow: no camera path to play (start with --camera-path FILE)\n");
                } else {
                    playing = !playing;
                    pathTime = 0.0;
                    std::fprintf(stderr, "meadow: camera path %s\n", playing ? "playing" : "stopped");
                }
            }
            if (requests.toggleRecording) {
                if (recorder.recording)
                    failures += recorder.stop(fly.pose()) ? 0 : 1;
                else
                    recorder.start(fly.pose());
            }
            screenshotPending = screenshotPending || requests.screenshot;

            // The camera: the path while it plays, else the keys and the mouse.
            if (in.mousePressed[size_t(MouseButton::Left)])
                leftDragOwned = !hudMouse;
            if (!in.button(MouseButton::Left))
                leftDragOwned = false;
            const bool looking = in.button(MouseButton::Right) || (in.button(MouseButton::Left) && leftDragOwned);
            if (playing) {
                pathTime += dt;
                fly.setPose(sampleCameraPath(*opt.path, opt.path->startTime() + pathTime));
                if (pathTime >= opt.path->duration()) {
                    playing = false;
                    std::fprintf(stderr, "meadow: camera path finished\n");
                }
            } else {
                fly.update(in, looking, !hudKeyboard, float(dt), &ground);
            }
            if (recorder.recording)
                recorder.step(dt, fly.pose());
            advanceDay(controls, dt);
            sceneSeconds += dt;

            const CameraPose pose = fly.pose();
            state.camera = baseCamera;
            state.camera.eye = pose.eye;
            state.camera.target = pose.target;
            state.width = targets.extent.width;
            state.height = targets.extent.height;
            state.seconds = sceneSeconds;
            applyControls(controls, state);
            updateFrame(renderer, state);

            VK_CHECK(vkResetCommandBuffer(window.cmd, 0));
            VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
            begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
            VK_CHECK(vkBeginCommandBuffer(window.cmd, &begin));
            recordFieldFrame(ctx, renderer, window.cmd, targets, &timer);
            recordFrameToComposite(window.cmd, window, targets);
            recordHud(ctx, hud, window.cmd, window, controls.showHud);
            recordCompositeToSwapchain(window.cmd, window, imageIndex, access::kColorAttachmentWrite);
            markTimestamp(timer, window.cmd, "window"); // copy, HUD and blit to the swapchain
            VK_CHECK(vkEndCommandBuffer(window.cmd));
            submitAndPresent(ctx, window, imageIndex);
            timerHasFrame = true;
            if (logThisFrame)
                printState(frame, fly, ground, controls, window, playing);
            ++frame;

            if (screenshotPending && window.compositeHasFrame) {
                screenshotPending = false;
                std::filesystem::path file = opt.outDir / ("meadow-" + scene.name + "-" + timestampText() + "-f" +
                                                           std::to_string(frame - 1) + ".png");
                try {
                    VK_CHECK(vkWaitForFences(ctx.device, 1, &window.frameFence, VK_TRUE, UINT64_MAX));
                    writeRgba8(file, window.composite.extent.width, window.composite.extent.height,
                               readCompositePixels(ctx, window));
                    hudStats.lastScreenshot = file.string();
                    std::fprintf(stderr, "meadow: screenshot %ux%u written to %s\n", window.composite.extent.width,
                                 window.composite.extent.height, file.string().c_str());
                } catch (const Error& e) {
                    std::fprintf(stderr, "meadow: error: %s\n", e.what());
                    ++failures;
                }
            }
        }
        VK_CHECK(vkDeviceWaitIdle(ctx.device));
        if (recorder.recording)
            failures += recorder.stop(fly.pose()) ? 0 : 1;
        if (player && !player->finished() && !quit)
            std::fprintf(stderr, "meadow: the window closed before the script ended\n");
        if (opt.screenshotOnExit) {
            if (frame == 0 || !window.compositeHasFrame)
                throw Error("meadow view: no frame is on screen, so there is no screenshot to write");
            writeRgba8(*opt.screenshotOnExit, window.composite.extent.width, window.composite.extent.height,
                       readCompositePixels(ctx, window));
            std::fprintf(stderr, "meadow: screenshot %ux%u written to %s\n", window.composite.extent.width,
                         window.composite.extent.height, opt.screenshotOnExit->string().c_str());
        }
        std::fprintf(stderr, "meadow: view showed %u frames; window %ux%u at exit\n", frame, window.extent.width,
                     window.extent.height);
        destroyHud(ctx, hud);
        destroyGpuTimer(ctx, timer);
        destroyRenderTargets(ctx, targets);
        destroyWindow(ctx, window);
        destroyFieldRenderer(ctx, renderer);
    }
    int status = validationExitStatus(ctx);
    destroyContext(ctx);
    terminateWindowSystem();
    if (failures > 0) {
        std::fprintf(stderr, "meadow: %d file%s could not be written (see above)\n", failures,
                     failures == 1 ? "" : "s");
        return status != 0 ? status : 1;
    }
    return status;
}

} // namespace meadow
