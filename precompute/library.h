// A scene's library: everything precomputed for it, loaded by the engine (DESIGN.md 2.9).
//
// Sections (little-endian, see core/library_file.h for the container):
//   "SCNE" the resolved scene as JSON text
//   "CLMP" the clumps: per clump its mesh at the mean pose, its motion basis and coordinates,
//          its motion graph and the statistics of its simulation
//   "ATLS" the plants' texture atlas: u32 width, u32 height, 8-bit sRGB RGBA texels
//   "TFLD" the field's clumps: u32 count, then per instance gpu::GpuInstance (4 + 4 words)
//   "LODS" per clump and LOD: original vertex indices, triangles, errors against the full mesh
//   "ROCK" the rocks: meshes, static light transfer, instances (library_field.h)
//   "PLCE" the terrain, the Wang tiles' and the field's placement figures
//   "LITE" per clump: SH order, the vertex and ground appearance models (mean, basis, per-frame
//          coordinates, error per mode), the ground grid, held-out errors
//   "SKYD" the day of sky: SH order, backdrop size, source (0 analytic, 1 panoramas), then per
//          frame its time, sun direction, radiance and irradiance, SH and backdrop image
#pragma once

#include "clump_light.h"
#include "clump_lod.h"
#include "clump_motion.h"
#include "gpu_types.h"
#include "library_field.h"
#include "mesh.h"
#include "scene.h"

#include <filesystem>
#include <string>
#include <vector>

namespace meadow {

// What the engine and `meadow inspect` need of one clump.
struct LibraryClump {
    std::string name;
    uint32_t plants = 0;
    Mesh mesh;                            // the mean pose, atlas UVs
    MotionBasis motion;                   // x̄ + U q per rod block; frames over all levels
    ClumpLight light;                     // transfer of the clump and its ground over the motion (timings not stored)
    std::array<ClumpLod, kLodCount> lods; // LOD 0 is the full mesh, reordered for the vertex cache
    MotionGraph graph;
    std::vector<LevelStats> levels;
};

struct Library {
    nlohmann::json scene; // resolved scene (preset merged, effective seed)
    std::vector<LibraryClump> clumps;
    RgbaImage atlas;
    std::vector<gpu::GpuInstance> field; // the clump instances (placement: library_field.h)
    LibraryField placement;              // terrain, rocks, tiling figures
    sky::SkyDay sky;
    bool skyFromMaps = false; // a user's panoramas rather than the analytic sky
    uint32_t formatVersion = 0;
    uint64_t inputHash = 0;
    uint64_t fileBytes = 0;
    std::vector<std::string> sections;
    double buildSeconds = 0.0; // as recorded when built
};

// What the library of `scene` would be built from, hashed: scene, preset, seed, format.
uint64_t libraryInputHash(const Scene& scene);

// Builds the library of `scene` and writes it to `path` (atomically). Progress goes to stderr.
void buildLibrary(const Scene& scene, const std::filesystem::path& path, bool quiet = false);
Library loadLibrary(const std::filesystem::path& path);

// Where the library of `scene` is cached: $MEADOW_CACHE_DIR, else $XDG_CACHE_HOME/meadow, else
// ~/.cache/meadow; the file name holds the scene name, preset and input hash.
std::filesystem::path cachedLibraryPath(const Scene& scene);

// The cached library of `scene`, built first if missing, stale or corrupt (never trusted).
Library ensureLibrary(const Scene& scene, bool quiet = false);

// The cached library of `scene` as it is: throws meadow::Error naming the path and the command that
// builds it when there is none, or when it was built from other inputs. For programs that run
// libraries but cannot build them (the bench runner); everything else calls ensureLibrary.
Library loadCachedLibrary(const Scene& scene);

} // namespace meadow
