// The field of a scene (docs/ARCHITECTURE.md, Placement): each clump's swept volume voxelised from
// its simulated frames, rocks made and voxelised, the Wang tiles filled by voxel dart throwing
// (placement/), the scene's stochastic tiling flattened onto the terrain and checked in 3D. What
// the library keeps of it: flat instance lists for the run time, rock meshes, and the figures
// inspect shows.
#pragma once

#include "library/field.h"

#include "gpu_types.h"
#include "library/mesh.h"
#include "library/terrain.h"
#include "pipeline/clump_motion.h"
#include "plants/rock.h"
#include "scene/scene.h"

#include <cstdint>
#include <vector>

namespace meadow {

struct PlacedField {
    // GpuInstance::mesh names the clump (clumps) or the rock (rocks); positionScale.w is +1, or -1
    // for an instance mirrored about the vertical plane that holds the wind direction.
    std::vector<gpu::GpuInstance> clumps;
    std::vector<gpu::GpuInstance> rocks;
    std::vector<RockMesh> rockMeshes;
    TerrainParams terrain;
    PlacementStats stats;
};

// `meshes[i]` is clump i as drawn (clumpRenderMesh of motions[i]). Deterministic.
PlacedField placeField(const Scene& scene, const std::vector<ClumpMotion>& motions, const std::vector<Mesh>& meshes);

} // namespace meadow
