// The field as the library keeps it: the clumps' instances, the rocks with their static light
// transfer and instances, the terrain and the figures of the placement that made
// them (placement/, pipeline/field_placement.h).
#pragma once

#include "gpu_types.h"
#include "library/far_samples.h"
#include "library/motion_basis.h"
#include "library/terrain.h"

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace meadow {

// What the placement did (placement/, pipeline/field_placement.h), as `meadow inspect` reports it.
struct PlacementStats {
    uint32_t tiles = 0;                  // tiles filled (the complete set)
    std::vector<uint32_t> clumpsPerTile; // per tile of the set
    std::vector<uint32_t> rocksPerTile;
    double densityVsPoissonDisc = 0.0; // voxel-tested clumps per area over disc-tested ones
    uint32_t overlapViolations = 0;    // over every tile and neighbour offset (must be 0)
    uint32_t tilesX = 0, tilesY = 0;
    float tileSize = 0.0f;
    uint32_t overlaps3dFound = 0; // pairs that met once placed on the terrain
    uint32_t clumpsRemoved3d = 0, rocksRemoved3d = 0;
    uint32_t overlapViolations3d = 0;        // left in the final field (must be 0)
    std::vector<float> sweptFootprintRadius; // per clump, m
    // The tiles of the set that the field's tiling uses (indices, ascending), and the disc
    // baseline's clumps per tile of the set, so that the field's figures can be taken over those.
    std::string tiling; // the field's tiling: "scanline" or "hash" (scene key field.tiling)
    std::vector<uint32_t> fieldTiles;
    std::vector<uint32_t> poissonClumpsPerTile;
    // Swept volumes are voxelised from some of each clump's simulated frames (sweptFrames of
    // simulatedFrames, per clump). The same overlap checks with volumes of every frame:
    std::vector<uint32_t> sweptFrames, simulatedFrames;
    uint32_t overlapViolationsAllFrames = 0;   // as overlapViolations (tile pairs)
    uint32_t overlapViolations3dAllFrames = 0; // as overlapViolations3d (pairs in the final field)
};

// A rock's mesh (plants/rock.h makes them).
struct RockMesh {
    std::string name;                 // "rock-<i>"
    float size = 0.0f;                // max(x extent, z extent) of the mesh (m)
    std::vector<glm::vec3> positions; // all with y >= 0; the cut rim exactly at y = 0
    std::vector<glm::vec3> normals;   // unit, outward
    std::vector<glm::vec2> uvs;       // top-down planar, in [0, 1]
    std::vector<uint32_t> indices;    // triangle list, counter-clockwise seen from outside
};

// The rocks' linear albedo, the same for every rock: the bake's and the renderer's.
inline constexpr glm::vec3 kRockAlbedo{0.30f, 0.28f, 0.25f};

// A rock's level of detail: a subset of its vertices and triangles over them.
struct RockLod {
    std::vector<uint32_t> vertices; // the rock's vertex indices, in first-use order
    std::vector<uint32_t> indices;  // triangles into `vertices`
};

// A rock as the library keeps it: the mesh, its levels of detail, and its transfer (static: one
// bake, no gradient) and that of the ground around it, in transfer/transfer.h's layouts.
struct LibraryRock {
    RockMesh mesh;
    std::array<RockLod, kLodCount> lods; // LOD 0 the whole mesh, ordered for the vertex cache
    int order = 0;
    std::vector<float> transfer; // vertices x 2 sides x 3 channels x order^2
    uint32_t groundResolution = 0;
    float groundSize = 0.0f;
    std::vector<float> groundTransfer; // resolution^2 points x 3 channels x order^2
    FarSamples far;                    // surface samples for the far field, over LOD 0, playing the last LOD's vertices
};

// The field: every instance of a clump or a rock on the terrain (docs/ARCHITECTURE.md).
struct LibraryField {
    std::vector<gpu::GpuInstance> clumpInstances; // mesh names the clump (Library::clumps)
    TerrainParams terrain;
    glm::vec2 windDirection{1.0f, 0.0f}; // (x, z) unit: mirrored instances reflect about its vertical plane
    PlacementStats stats;
    std::vector<LibraryRock> rocks;
    std::vector<gpu::GpuInstance> rockInstances; // mesh names the rock
};

} // namespace meadow
