// Soak test (issue 10, item 4): thousands of offscreen frames of the default scene's ci field while
// the day goes round and the wind gusts, under the validation layer. Passes when
//   - meadow's GPU allocations (MemoryAllocator::bytesInUse), resident memory (/proc/self/statm)
//     and the C heap's live bytes (mallinfo2) each grow by less than 1 % from frame kSteadyFrame to
//     the end: nothing accumulates per frame, whatever the sky and wind do;
//   - the validation layer (synchronization validation included) sent no message;
//   - the frames are not all the same: time, sky and wind really moved.
// Memory is sampled after every frame, before any read-back, and the floor (least value) of the
// kWindow frames from kSteadyFrame is compared with the floor of the last kWindow: lavapipe frees
// some 20 MiB of a frame's work at no fixed moment, so single samples swing while the floor is
// what stays live. Resident memory is measured with glibc's trimming off (see main), so it is the
// high-water mark of the heap; the heap's live bytes catch what resident memory would hide in
// memory freed earlier (a leak of 4 KiB a frame grows them by about 4 % over the run).
// Small images (64 x 36) and a sky that moves once a second keep the run to about a minute on two
// cores.
//   meadow_soak_test [FRAMES]     (default 3000; the scene comes from MEADOW_SOURCE_DIR)
#include "core/error.h"
#include "pipeline/build_library.h"
#include "render/field_content.h"
#include "render/offscreen.h"
#include "render/render_targets.h"
#include "vk/context.h"
#include "vk/memory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <malloc.h>
#include <unistd.h>

namespace {

using namespace meadow;

// After one whole swing of the wind (20 s, below) every wind level and gust state has been met once,
// so the driver's caches, pools and shader compiles have settled and the memory allocators of its
// threads have reached their working size (on an AVX-512 machine that took up to frame ~500).
constexpr uint32_t kSteadyFrame = 600;
constexpr uint32_t kWindow = 100;   // frames whose floor is compared, from kSteadyFrame and at the end
constexpr double kMaxGrowth = 0.01; // 1 %
constexpr uint32_t kSkyStep = 30;   // frames between moves of the sky

uint64_t residentBytes() {
    std::ifstream statm("/proc/self/statm");
    uint64_t size = 0, resident = 0;
    statm >> size >> resident;
    return resident * uint64_t(sysconf(_SC_PAGESIZE));
}

// Bytes the C heap holds for live allocations (all arenas, and the blocks mapped on their own).
uint64_t heapBytes() {
    const struct mallinfo2 info = mallinfo2();
    return uint64_t(info.uordblks) + uint64_t(info.hblkhd);
}

// The least of values[begin, end): what stayed live through those frames.
uint64_t floorOf(const std::vector<uint64_t>& values, size_t begin, size_t end) {
    return *std::min_element(values.begin() + std::ptrdiff_t(begin), values.begin() + std::ptrdiff_t(end));
}

uint64_t hashPixels(const std::vector<uint8_t>& pixels) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (uint8_t p : pixels)
        h = (h ^ p) * 0x100000001b3ull;
    return h;
}

struct Series {
    const char* name;
    std::vector<uint64_t> samples; // one per frame
};

// Prints the series' floors at kSteadyFrame and at the end; false if it grew by kMaxGrowth or more.
bool flat(const Series& s, uint32_t frames) {
    const uint64_t steady = floorOf(s.samples, kSteadyFrame, kSteadyFrame + kWindow);
    const uint64_t end = floorOf(s.samples, frames - kWindow, frames);
    const double growth = steady == 0 ? 0.0 : (double(end) - double(steady)) / double(steady);
    std::printf("%-9s frames %u-%u: %12llu bytes   frames %u-%u: %12llu bytes   %+.3f %%\n", s.name, kSteadyFrame,
                kSteadyFrame + kWindow - 1, static_cast<unsigned long long>(steady), frames - kWindow, frames - 1,
                static_cast<unsigned long long>(end), 100.0 * growth);
    if (growth < kMaxGrowth)
        return true;
    std::printf("FAIL: %s grew by 1 %% or more\n", s.name);
    return false;
}

int run(uint32_t frames) {
    if (frames < kSteadyFrame + 2 * kWindow) {
        std::printf("FAIL: %u frames are too few (at least %u)\n", frames, kSteadyFrame + 2 * kWindow);
        return 1;
    }
    const Scene scene = loadScene(MEADOW_SOURCE_DIR "/data/scenes/irises.json", "ci", std::nullopt);
    const Library library = ensureLibrary(scene, true);

    Context context;
    ContextOptions options;
    options.validation = true;
    createContext(context, options);
    int status = 0;
    {
        FieldRenderer renderer = createFieldRenderer(context, fieldClumps(library), fieldInstances(library),
                                                     library.atlas, fieldScenery(library));
        const uint32_t width = 64, height = 36;
        Offscreen offscreen = createOffscreen(context, {width, height});
        FrameState state;
        state.camera.eye = scene.camera.eye;
        state.camera.target = scene.camera.target;
        state.camera.fovYDegrees = scene.camera.fovYDegrees;
        state.width = width;
        state.height = height;
        const float topLevel = float(scene.wind.levelSpeeds.size() - 1);

        Series gpu{"GPU", {}}, resident{"resident", {}}, heap{"heap", {}};
        std::vector<uint64_t> imageHashes;
        for (Series* s : {&gpu, &resident, &heap})
            s->samples.reserve(frames); // the test's own records must not grow the heap it measures
        imageHashes.reserve(frames / 250 + 2);
        for (uint32_t i = 0; i < frames; ++i) {
            state.seconds = double(i) / 30.0 + 1e-6;
            // One whole day over the run, from before dawn, the sky moving on once a second of scene
            // time: each move re-lights every clump vertex (the light pass), which on lavapipe costs
            // five plain frames, so moving it every frame would make the run five times longer
            // without exercising anything more.
            const uint32_t skyFrame = i - i % kSkyStep;
            state.hours = std::fmod(4.0 + 24.0 * double(skyFrame) / double(frames), 24.0);
            // Gusting: the base level swings from calm to the strongest level and back every 20 s,
            // with gusts of changing strength on top.
            state.wind.baseLevel = float(0.5 * topLevel * (1.0 - std::cos(2.0 * M_PI * state.seconds / 20.0)));
            state.wind.gustAmplitude = 0.5f + 0.5f * float(std::sin(state.seconds * 0.7));
            renderOffscreenFrame(context, renderer, offscreen, state);
            gpu.samples.push_back(context.memory->bytesInUse());
            resident.samples.push_back(residentBytes());
            heap.samples.push_back(heapBytes());
            // Read an image back now and then, as `meadow render` does every frame.
            if (i % 250 == 0 || i + 1 == frames)
                imageHashes.push_back(hashPixels(readLdrPixels(context, offscreen.targets)));
            if (i % 500 == 0)
                std::printf("frame %5u  %5.2f h  wind %.2f  GPU %.1f MiB  resident %.1f MiB  heap %.1f MiB\n", i,
                            state.hours, double(state.wind.baseLevel), double(gpu.samples.back()) / 1048576.0,
                            double(resident.samples.back()) / 1048576.0, double(heap.samples.back()) / 1048576.0);
        }
        for (const Series* s : {&gpu, &resident, &heap})
            if (!flat(*s, frames))
                status = 1;

        std::sort(imageHashes.begin(), imageHashes.end());
        const size_t distinct = size_t(std::unique(imageHashes.begin(), imageHashes.end()) - imageHashes.begin());
        std::printf("%zu of %zu images read back are distinct\n", distinct, imageHashes.size());
        if (distinct < 3) {
            std::printf("FAIL: the frames hardly change; the day and the wind did not move\n");
            status = 1;
        }
        destroyOffscreen(context, offscreen);
        destroyFieldRenderer(context, renderer);
    }
    const uint32_t messages = context.validation->total();
    std::printf("validation messages: %u\n", messages);
    if (messages != 0) {
        std::printf("FAIL: the validation layer reported %u messages\n", messages);
        status = 1;
    }
    destroyContext(context);
    return status;
}

} // namespace

int main(int argc, char** argv) {
    // glibc hands freed memory back to the system in bursts, so resident memory swings by several
    // per cent from frame to frame with nothing leaking. With trimming off, and only allocations
    // above 32 MiB (meadow's memory blocks) mapped on their own, resident memory is the heap's
    // high-water mark instead. The setting must be there when the process starts, so the test
    // restarts itself with it.
    if (!std::getenv("GLIBC_TUNABLES")) {
        setenv("GLIBC_TUNABLES", "glibc.malloc.trim_threshold=4294967296:glibc.malloc.mmap_threshold=33554432", 1);
        execv("/proc/self/exe", argv);
        std::perror("meadow_soak_test: cannot restart itself");
        return 1;
    }
    const uint32_t frames = argc > 1 ? uint32_t(std::strtoul(argv[1], nullptr, 10)) : 3000;
    try {
        const int status = run(frames);
        std::printf(status == 0 ? "PASS\n" : "FAIL\n");
        return status;
    } catch (const meadow::Error& e) {
        std::fprintf(stderr, "meadow_soak_test: error: %s\n", e.what());
        return 1;
    }
}
