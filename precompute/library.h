// A scene's library: everything precomputed for it, loaded by the engine. For now it holds the
// resolved scene and the test field's instances; later stages add their sections.
//
// Sections: "SCNE" the resolved scene as JSON text; "TMSH" the stand-in plant mesh (u32
// vertex count, u32 index count, f32 bounding radius, then 8 floats per vertex and the u32
// indices); "TFLD" the test field (u32 count, then per instance the 8 floats of
// gpu::GpuInstance).
#pragma once

#include "gpu_types.h"
#include "scene.h"
#include "test_mesh.h"

#include <filesystem>
#include <string>
#include <vector>

namespace meadow {

struct Library {
    nlohmann::json scene; // resolved scene (preset merged, effective seed)
    Mesh testMesh;
    std::vector<gpu::GpuInstance> testField;
    uint32_t formatVersion = 0;
    uint64_t inputHash = 0;
    uint64_t fileBytes = 0;
    std::vector<std::string> sections;
};

// What the library of `scene` would be built from, hashed: scene, preset, seed, format.
uint64_t libraryInputHash(const Scene& scene);

// The test field's instances: a jittered grid centred on the origin, random yaw, scale, tint.
std::vector<gpu::GpuInstance> placeTestField(const Scene& scene, float meshRadius);

// Builds the library of `scene` and writes it to `path` (atomically). Progress goes to stderr.
void buildLibrary(const Scene& scene, const std::filesystem::path& path, bool quiet = false);
Library loadLibrary(const std::filesystem::path& path);

// Where the library of `scene` is cached: $MEADOW_CACHE_DIR, else $XDG_CACHE_HOME/meadow, else
// ~/.cache/meadow; the file name holds the scene name, preset and input hash.
std::filesystem::path cachedLibraryPath(const Scene& scene);

// The cached library of `scene`, built first if missing, stale or corrupt (never trusted).
Library ensureLibrary(const Scene& scene, bool quiet = false);

} // namespace meadow
