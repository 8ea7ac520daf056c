// The motion library of one clump (docs/ARCHITECTURE.md, Wind and rods; Motion): the clump
// simulated in every wind level, its vertex motion reduced by PCA, and the wind-indexed motion
// graph over the frames.
#pragma once

#include "library/clump.h"

#include "library/mesh.h"
#include "motion/block_pca.h"
#include "motion/motion_graph.h"
#include "plants/plant.h"
#include "scene/scene.h"

#include <array>
#include <vector>

namespace meadow {

struct ClumpMotion {
    PlantClump clump;                     // rest geometry and rods
    std::vector<glm::vec3> meanPositions; // per vertex: the PCA mean (x̄)
    std::vector<glm::vec3> meanNormals;   // per vertex: skinned normals averaged over all frames
    BlockPcaResult pca;                   // of the stacked vertex positions, one block per rod
    MotionBasis basis;                    // what the library stores: per-LOD modes, rows, coordinates
    std::vector<MotionClip> clips;        // one per level, in frame order
    MotionGraph graph;
    std::vector<LevelStats> levels;
    double simulateSeconds = 0.0, pcaSeconds = 0.0, graphSeconds = 0.0;
};

// The relative PCA error each LOD allows: LOD0 takes the scene's bound, far LODs far more.
std::array<float, kLodCount> lodErrorBounds(float lod0MaxError);

// Simulates, reduces and builds the graph for one clump. Deterministic for the same inputs.
ClumpMotion buildClumpMotion(const PlantClump& clump, const Scene& scene, uint64_t seed);

// The clump at its mean pose as the engine draws it (atlas UVs, mean normals).
Mesh clumpRenderMesh(const ClumpMotion& motion);

} // namespace meadow
