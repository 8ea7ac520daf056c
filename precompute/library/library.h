// A scene's library: everything the precompute made for it, the one contract between the
// precompute (which writes it) and the engine (which reads it). docs/ARCHITECTURE.md, The library.
//
// Sections of the container (library_file.h), little-endian, one file each in library/:
//   "SCNE" the resolved scene as JSON text                                  scene_section.cpp
//   "CLMP" the clumps: per clump its mesh at the mean pose, its motion basis and coordinates,
//          its motion graph and the statistics of its simulation             clump_section.cpp
//   "ATLS" the plants' texture atlas: u32 width, u32 height, 8-bit sRGB RGBA  atlas_section.cpp
//   "TFLD" the field's clumps: u32 count, then per instance gpu::GpuInstance  instance_section.cpp
//   "LODS" per clump and LOD: original vertex indices, triangles, errors against the full mesh
//                                                                            lod_section.cpp
//   "ROCK" the rocks: meshes, static light transfer, instances                rock_section.cpp
//   "PLCE" the terrain, the Wang tiles' and the field's placement figures    placement_section.cpp
//   "LITE" per clump: SH order, the vertex and ground appearance models (mean, basis, per-frame
//          coordinates, error per mode), the ground grid, held-out errors    light_section.cpp
//   "SKYD" the day of sky: SH order, backdrop size, source (0 analytic, 1 panoramas), then per
//          frame its time, sun direction, radiance and irradiance, SH and backdrop image
//                                                                            sky_section.cpp
//   "FARS" the far field's surface samples (library/far_samples.h): u32 clump count, then per
//          clump f32 area, u32 count, count x {f32 x, y, z; u32 normal, albedo, vertex}; the
//          same for the rocks                                                far_samples_section.cpp
#pragma once

#include "gpu_types.h"
#include "library/clump.h"
#include "library/field.h"
#include "library/mesh.h"
#include "library/sky_day.h"

#include <filesystem>
#include <string>
#include <vector>

namespace meadow {

// The resolved scene (preset merged, effective seed) as the SCNE section holds it, JSON text, and
// what the run time reads of it.
struct LibraryScene {
    std::string json;
    std::string name;
    uint64_t seed = 0;
    float yawJitter = 0.3f; // field.yawJitter, or the scene's default (scene/scene.h)
};

// Reads name, seed and field.yawJitter from the resolved scene's JSON text; throws meadow::Error
// naming `where` when the text is not JSON or not a resolved scene.
LibraryScene parseLibraryScene(std::string json, const std::string& where);

struct Library {
    LibraryScene scene;
    std::vector<LibraryClump> clumps;
    RgbaImage atlas;
    LibraryField field; // terrain, instances of clumps and rocks, rocks, placement figures
    sky::SkyDay sky;
    bool skyFromMaps = false; // a user's panoramas rather than the analytic sky
    // Read from the container, not written by writeLibrary:
    uint32_t formatVersion = 0;
    uint64_t inputHash = 0;
    uint64_t fileBytes = 0;
    std::vector<std::string> sections;
};

// Reads and checks every section; throws meadow::Error naming the file, the section and the
// problem.
Library loadLibrary(const std::filesystem::path& path);

// Writes `library` to `path` atomically (library_file.h), with the hash of what it was built from.
void writeLibrary(const std::filesystem::path& path, const Library& library, uint64_t inputHash);

} // namespace meadow
