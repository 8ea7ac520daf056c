// libFuzzer target: the glTF import path (precompute/plants/gltf_import.h importGltfPlant), through
// tinygltf, as .glb when the input starts with glTF's binary magic and as .gltf otherwise.
#include "core/error.h"
#include "fuzz_input.h"
#include "plants/gltf_import.h"

#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace meadow;
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::filesystem::path path = fuzz::writeInput(binary ? "plant.glb" : "plant.gltf", data, size);
    try {
        const PlantClump plant = importGltfPlant(path);
        // What the importer promises (gltf_import.h): one rod, every vertex bound to it, finite.
        if (plant.rods.size() != 1 || plant.mesh.skin.size() != plant.mesh.positions.size())
            __builtin_trap();
    } catch (const Error&) {
    }
    return 0;
}
