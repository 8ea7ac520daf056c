// The field of a scene (DESIGN.md 2.7): each clump's swept volume voxelised from its simulated
// frames, rocks made and voxelised, the Wang tiles filled by voxel dart throwing (placement/),
// the scene's stochastic tiling flattened onto the terrain and checked in 3D. What the library
// keeps of it: flat instance lists for the run time, rock meshes, and the figures inspect shows.
#pragma once

#include "clump_motion.h"
#include "gpu_types.h"
#include "mesh.h"
#include "placement/terrain.h"
#include "plants/rock.h"
#include "scene.h"

#include <cstdint>
#include <vector>

namespace meadow {

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
};

struct PlacedField {
    // GpuInstance::mesh names the clump (clumps) or the rock (rocks); positionScale.w is +1, or -1
    // for an instance mirrored about the vertical plane that holds the wind direction.
    std::vector<gpu::GpuInstance> clumps;
    std::vector<gpu::GpuInstance> rocks;
    std::vector<RockMesh> rockMeshes;
    TerrainParams terrain;
    PlacementStats stats;
};

// The ground as drawn: the terrain over the field (tilesX x tilesY tiles of tileSize, centred on
// the origin) plus `margin` metres, sampled every `spacing` metres, exact at the grid points
// inside the field; over the margin it eases down to a flat plain at y = -amplitude - 5 cm, which
// a ring of four large quads carries out to the horizon. Normals from the drawn heights; UVs unused.
Mesh makeTerrainMesh(const TerrainParams& terrain, glm::vec2 fieldHalfExtent, float margin, float spacing);

// `meshes[i]` is clump i as drawn (clumpRenderMesh of motions[i]). Deterministic.
PlacedField placeField(const Scene& scene, const std::vector<ClumpMotion>& motions, const std::vector<Mesh>& meshes);

} // namespace meadow
