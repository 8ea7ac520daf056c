// Scene files (JSON): what a field contains and how it is shown. A scene has a base description
// and per-preset overrides ("presets": {"ci": {...}, "full": {...}}) merged over the base with
// JSON merge patch (RFC 7386). Loading checks every key and value and throws meadow::Error
// naming the file and the key.
#pragma once

#include "sky/sky_day.h"
#include "transfer/transfer.h"
#include <array>
#include <cstdint>
#include <filesystem>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace meadow {

// The field (docs/ARCHITECTURE.md, Placement): Wang tiles filled by voxel dart throwing, tiled over
// a terrain.
struct FieldSpec {
    uint32_t tilesX = 15, tilesY = 15; // the paper's 15 x 15
    float tileSize = 6.0f;             // m, edge of a Wang tile
    float cellSize = 0.025f;           // m, voxel edge of the swept volumes
    float margin = 0.025f;             // m, safety dilation of every swept volume
    float yawJitter = 0.3f;            // rad: clumps turn at most this far (the wind has one direction)
    uint32_t rocksPerTile = 10;        // at most
    uint32_t rockVariants = 4;
    uint32_t sweptFrames = 128; // motion frames voxelised per clump, half from the strongest level
    // How tiles are laid: "scanline" (Cohen et al.'s stochastic scan-line tiling from their 8
    // tiles, the paper's) or "hash" (each edge's colour a hash of its coordinates, from all 16:
    // any tile of an unbounded field is known without its neighbours).
    std::string tiling = "scanline";
    float terrainAmplitude = 1.0f;   // m, heights within +-amplitude
    float terrainWavelength = 40.0f; // m, of the first of three octaves
};

struct SceneCamera {
    glm::vec3 eye{0.0f, 2.0f, -10.0f};
    glm::vec3 target{0.0f};
    float fovYDegrees = 55.0f;
};

// Where the clumps come from: procedural irises, or a user's glTF plant.
struct PlantsParams {
    std::string source = "iris"; // "iris" or "gltf"
    uint32_t clumps = 4;         // procedural clump variants
    std::filesystem::path gltf;  // source "gltf": the file, relative to the scene file
    // source "gltf": the imported rod's stem diameter (m), which sets its bending stiffness
    // (plants/gltf_import.h); none: the importer's default. Refused with source "iris".
    std::optional<float> stemDiameter;
};

// The wind the clumps are simulated in: one direction, one mean speed per level (calm first).
struct WindParams {
    glm::vec3 direction{1.0f, 0.0f, 0.0f};                  // horizontal unit vector
    std::vector<float> levelSpeeds{0.7f, 2.0f, 4.0f, 7.0f}; // m/s at 1 m
    float turbulence = 0.3f;
    float gustPeriod = 4.0f; // s
};

// How long each level is simulated and how the motion is reduced.
struct MotionParams {
    float frameRate = 30.0f;     // recorded frames per second
    uint32_t substeps = 20;      // rod substeps per frame
    float settleSeconds = 2.0f;  // simulated before recording
    float recordSeconds = 20.0f; // recorded per level
    float lod0MaxError = 0.01f;  // relative PCA error allowed at LOD0
};

// The sky over a day (docs/ARCHITECTURE.md, Sky): the analytic daylight sky, or a user's HDR
// panoramas spread over the day in its place.
struct SkySource {
    sky::SkyParams params;                   // preset defaults, overridden by the scene
    std::vector<std::filesystem::path> maps; // EXR/HDR panoramas, relative to the scene file; empty: analytic
};

// How the clumps' light transfer is baked and reduced (docs/ARCHITECTURE.md, Light transfer).
struct LightParams {
    transfer::BakeSettings bake;      // preset defaults (transfer::bakeSettingsForPreset), overridden by the scene
    uint32_t framesPerLevel = 12;     // motion frames baked per wind level, first and last included (ci: 8)
    float appearanceMaxError = 0.02f; // relative to the transfer itself
    uint32_t maxAppearanceModes = 16;
};

// Levels of detail (docs/ARCHITECTURE.md, Levels of detail): each LOD's triangle budget as a
// fraction of the full mesh. The default's last LOD keeps ~30 triangles per iris, one or two per
// leaf and petal: below that whole leaves and flowers must go, which shows as a change of colour
// and density at distance.
struct LodParams {
    std::array<float, 5> triangleFractions{1.0f, 1.0f / 3.0f, 1.0f / 10.0f, 1.0f / 20.0f, 1.0f / 30.0f};
};

// The far field's surface samples (library/far_samples.h): not a scene key, set by the preset
// (full 4096 per clump and rock, ci 1024).
struct FarParams {
    uint32_t samplesPerClump = 4096;
};

struct Scene {
    std::filesystem::path path;
    std::string name;
    std::string preset; // "ci" or "full"
    uint64_t seed = 0;
    FieldSpec field;
    SceneCamera camera;
    float timeOfDay = 12.0f; // local solar hours
    PlantsParams plants;
    WindParams wind;
    MotionParams motion;
    SkySource sky;
    LightParams light;
    LodParams lod;
    FarParams far;
    nlohmann::json resolved; // the scene after the preset merge, with the effective seed
};

inline constexpr const char* kPresetNames[] = {"ci", "full"};

// `seed` overrides the scene's own seed when given.
Scene loadScene(const std::filesystem::path& path, const std::string& preset, std::optional<uint64_t> seed);

} // namespace meadow
