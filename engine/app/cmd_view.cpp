// meadow view: the interactive walkthrough window.
#include "app/commands.h"
#include "app/session.h"
#include "core/error.h"
#include "io/image_io.h"
#include "render/field_renderer.h"
#include "render/window.h"
#include "vk/timestamps.h"
#include "vk/vk_check.h"

#include <GLFW/glfw3.h>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace meadow {
namespace {

const char* kViewHelp = R"(usage: meadow view SCENE [options]

Opens the walkthrough: a window onto the field.

controls:
  W A S D         move forward, left, back, right      Q / E   down / up
  left mouse drag look around                          Shift   move 5x faster
  Esc             quit

options:
  --size WxH            initial window size (default 1280x720)
  --time-of-day H       local solar hour, 0-24 (default: the scene's)
  --camera EX,EY,EZ,TX,TY,TZ   initial eye and target (default: the scene's)
  --no-vsync            present without waiting for vertical blank when the driver allows
  --frames N            quit by itself after N frames (for scripts and tests)
  --resize WxH          after a third of --frames, resize the window to WxH (tests)
  --minimize            after two thirds of --frames, minimise the window for half a second,
                        then restore it (tests; needs a window manager)
  --screenshot FILE     on exit, write the last frame shown to FILE (.png)
  --preset, --seed, --device, --validation, --verbose   as for meadow render
)";

// A free-flying camera steered by keys and mouse drags.
struct FlyCamera {
    glm::vec3 eye;
    float yaw;   // radians around +y, 0 looks along +z
    float pitch; // radians, positive looks up
    double lastX = 0.0, lastY = 0.0;
    bool dragging = false;

    explicit FlyCamera(const Camera& c) : eye(c.eye) {
        glm::vec3 d = glm::normalize(c.target - c.eye);
        yaw = std::atan2(d.x, d.z);
        pitch = std::asin(std::clamp(d.y, -1.0f, 1.0f));
    }
    glm::vec3 forward() const {
        return {std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch)};
    }
    void update(GLFWwindow* window, float dt) {
        double x, y;
        glfwGetCursorPos(window, &x, &y);
        bool down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        if (down && dragging) {
            yaw -= float(x - lastX) * 0.003f;
            pitch = std::clamp(pitch - float(y - lastY) * 0.003f, -1.5f, 1.5f);
        }
        dragging = down;
        lastX = x;
        lastY = y;
        glm::vec3 f = forward();
        glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0.0f, 1.0f, 0.0f)));
        float speed = (glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ? 25.0f : 5.0f) * dt;
        auto key = [&](int k) { return glfwGetKey(window, k) == GLFW_PRESS ? 1.0f : 0.0f; };
        eye += f * speed * (key(GLFW_KEY_W) - key(GLFW_KEY_S));
        eye += right * speed * (key(GLFW_KEY_D) - key(GLFW_KEY_A));
        eye.y += speed * (key(GLFW_KEY_E) - key(GLFW_KEY_Q));
    }
};

} // namespace

int runView(const Args& argv) {
    if (printHelpIfAsked(argv, kViewHelp))
        return 0;
    CommandSpec spec{"view",
                     {"SCENE"},
                     {"--size", "--time-of-day", "--camera", "--frames", "--resize", "--screenshot"},
                     {"--no-vsync", "--minimize"}};
    addSceneOptions(spec);
    addEngineOptions(spec);
    ParsedArgs args = parseArgs(spec, argv);
    auto [width, height] = args.size("--size", {1280, 720});
    uint32_t maxFrames = args.u32("--frames", 0, 1, 10'000'000);
    std::optional<std::pair<uint32_t, uint32_t>> resizeTo;
    if (args.has("--resize")) {
        if (!args.has("--frames"))
            throw Error("meadow view: --resize needs --frames");
        resizeTo = args.size("--resize", {0, 0});
    }
    bool minimizeTest = args.has("--minimize");
    if (minimizeTest && !args.has("--frames"))
        throw Error("meadow view: --minimize needs --frames");
    std::optional<std::filesystem::path> screenshot;
    if (auto s = args.value("--screenshot")) {
        if (imageKindForPath(*s) != ImageFileKind::Png)
            throw Error("meadow view: --screenshot " + *s + ": screenshots are PNG");
        checkOutputWritable(*s);
        screenshot = *s;
    }
    Scene scene = sceneFromArgs(args);
    float timeOfDay = args.f32("--time-of-day", scene.timeOfDay, 0.0f, 24.0f);
    FlyCamera fly(cameraFromArgs(args, scene));
    Library library = ensureLibrary(scene);

    initWindowSystem();
    ContextOptions options = contextOptionsFromArgs(args);
    options.instanceExtensions = windowInstanceExtensions();
    options.presentation = true;
    options.presentSupport = windowPresentSupport;
    Context ctx;
    createContext(ctx, options);
    int status = 0;
    {
        FieldRenderer renderer = createFieldRenderer(ctx, fieldClumps(library), fieldInstances(library), library.atlas,
                                                     fieldScenery(library));
        Window window = createWindow(ctx, "meadow — " + scene.name, width, height);
        window.vsync = !args.has("--no-vsync");
        GpuTimer timer = createGpuTimer(ctx, 16);
        RenderTargets targets{};
        FrameState state;
        state.hours = timeOfDay;
        auto started = std::chrono::steady_clock::now();

        uint32_t frame = 0;
        uint32_t generation = 0;
        bool timerHasFrame = false;
        auto last = std::chrono::steady_clock::now();
        double fpsClock = 0.0;
        uint32_t fpsFrames = 0;
        bool paused = false, minimizeRequested = false;
        std::chrono::steady_clock::time_point pausedSince;
        while (!glfwWindowShouldClose(window.window)) {
            glfwPollEvents();
            if (glfwGetKey(window.window, GLFW_KEY_ESCAPE) == GLFW_PRESS)
                break;
            if (maxFrames && frame >= maxFrames)
                break;
            if (resizeTo && frame == maxFrames / 3)
                glfwSetWindowSize(window.window, int(resizeTo->first), int(resizeTo->second));

            if (minimizeTest && !minimizeRequested && frame == 2 * maxFrames / 3) {
                glfwIconifyWindow(window.window);
                minimizeRequested = true;
                // The window manager acts asynchronously; give it up to two seconds.
                auto asked = std::chrono::steady_clock::now();
                while (!glfwGetWindowAttrib(window.window, GLFW_ICONIFIED) &&
                       std::chrono::steady_clock::now() - asked < std::chrono::seconds(2))
                    glfwWaitEventsTimeout(0.05);
            }

            // Minimised (iconified, or a zero-sized framebuffer on platforms that shrink it):
            // nothing is visible, so render nothing and wait for the window to come back.
            VkExtent2D fb = framebufferExtent(window);
            if (fb.width == 0 || fb.height == 0 || glfwGetWindowAttrib(window.window, GLFW_ICONIFIED)) {
                auto now = std::chrono::steady_clock::now();
                if (!paused) {
                    std::fprintf(stderr, "meadow: window minimised; rendering paused\n");
                    paused = true;
                    pausedSince = now;
                }
                if (minimizeTest && now - pausedSince > std::chrono::milliseconds(500))
                    glfwRestoreWindow(window.window);
                glfwWaitEventsTimeout(0.05);
                continue;
            }
            if (paused) {
                std::fprintf(stderr, "meadow: window restored; rendering resumed\n");
                paused = false;
                last = std::chrono::steady_clock::now();
            }
            if (window.swapchain == VK_NULL_HANDLE || fb.width != window.extent.width ||
                fb.height != window.extent.height) {
                if (!recreateSwapchain(ctx, window))
                    continue;
            }
            if (generation != window.swapchainGeneration) {
                // Render at the window's size so the blit is 1:1.
                VK_CHECK(vkDeviceWaitIdle(ctx.device));
                destroyRenderTargets(ctx, targets);
                targets = createRenderTargets(ctx, window.extent);
                generation = window.swapchainGeneration;
            }

            VK_CHECK(vkWaitForFences(ctx.device, 1, &window.frameFence, VK_TRUE, UINT64_MAX));
            if (timerHasFrame) {
                double gpuTotal = 0.0;
                for (const PassTime& p : readTimestamps(ctx, timer))
                    gpuTotal += p.milliseconds;
                if (fpsClock > 2.0) {
                    FieldStats stats = readFieldStats(renderer);
                    std::fprintf(stderr, "meadow: %.1f fps, GPU %.2f ms, %u of %u instances visible\n",
                                 double(fpsFrames) / fpsClock, gpuTotal, stats.visibleInstances, stats.testedInstances);
                    fpsClock = 0.0;
                    fpsFrames = 0;
                }
            }
            uint32_t imageIndex = 0;
            if (!acquireImage(ctx, window, imageIndex))
                continue;
            VK_CHECK(vkResetFences(ctx.device, 1, &window.frameFence));

            auto now = std::chrono::steady_clock::now();
            float dt = std::min(std::chrono::duration<float>(now - last).count(), 0.1f);
            last = now;
            fpsClock += dt;
            ++fpsFrames;
            fly.update(window.window, dt);
            Camera camera = cameraFromArgs(args, scene);
            camera.eye = fly.eye;
            camera.target = fly.eye + fly.forward();
            state.camera = camera;
            state.width = targets.extent.width;
            state.height = targets.extent.height;
            state.seconds = std::chrono::duration<double>(now - started).count();
            updateFrame(renderer, state);

            VK_CHECK(vkResetCommandBuffer(window.cmd, 0));
            VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
            begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
            VK_CHECK(vkBeginCommandBuffer(window.cmd, &begin));
            recordFieldFrame(ctx, renderer, window.cmd, targets, &timer);
            recordBlitToSwapchain(window.cmd, window, imageIndex, targets);
            VK_CHECK(vkEndCommandBuffer(window.cmd));
            submitAndPresent(ctx, window, imageIndex);
            timerHasFrame = true;
            ++frame;
        }
        VK_CHECK(vkDeviceWaitIdle(ctx.device));
        if (screenshot) {
            if (frame == 0)
                throw Error("meadow view: no frame was shown, so there is no screenshot to write");
            writeRgba8(*screenshot, targets.extent.width, targets.extent.height, readLdrPixels(ctx, targets));
            std::fprintf(stderr, "meadow: screenshot %ux%u written to %s\n", targets.extent.width,
                         targets.extent.height, screenshot->string().c_str());
        }
        std::fprintf(stderr, "meadow: view showed %u frames; window %ux%u at exit\n", frame, window.extent.width,
                     window.extent.height);
        destroyGpuTimer(ctx, timer);
        destroyRenderTargets(ctx, targets);
        destroyWindow(ctx, window);
        destroyFieldRenderer(ctx, renderer);
    }
    status = validationExitStatus(ctx);
    destroyContext(ctx);
    terminateWindowSystem();
    return status;
}

} // namespace meadow
