// libFuzzer target: the scene parser (precompute/scene/scene.h loadScene), both presets. A scene that
// loads must also hash (what the library cache names it by) when it names no outside files.
#include "core/error.h"
#include "fuzz_input.h"
#include "pipeline/build_library.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace meadow;
    const std::filesystem::path path = fuzz::writeInput("scene.json", data, size);
    for (const char* preset : kPresetNames) {
        try {
            const Scene scene = loadScene(path, preset, std::nullopt);
            // Outside files are read whole to hash them; the fuzzer must not send it to /dev or /proc.
            if (scene.plants.source != "gltf" && scene.sky.maps.empty())
                (void)libraryInputHash(scene);
        } catch (const Error&) {
        }
    }
    return 0;
}
