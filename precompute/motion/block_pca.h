// Motion reduced per rod (block PCA): x(t) = x̄ + U q(t) with U block-diagonal, one block per
// rod, since every vertex follows exactly one rod (plants/plant.h, SkinBinding).
//
// Why not one PCA of the whole clump: the ~50 blades of a clump flutter largely independently in
// turbulent wind, so a clump-wide basis needs hundreds of modes for 1 % error (docs/BENCHMARKS.md,
// first table), and every vertex would pay for all of them at run time. Per rod, a few modes carry
// a blade (its motion lives in the span of its ~10 nodes), and a vertex costs only its own rod's
// modes. The total count of modes for a given error is close to the clump-wide PCA's (Eckart–Young
// makes that one optimal), but the per-vertex cost falls by an order of magnitude.
//
// Modes are kept greedily by singular value across all blocks: the first k modes overall are the
// k largest singular values, which is the least-error block-diagonal basis with k columns, and
// each block's kept modes are always a prefix of its own (descending) modes — so a far LOD is
// simply fewer modes per block.
#pragma once

#include "library/motion_basis.h"
#include "motion/pca.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace meadow {

struct BlockPcaResult {
    Eigen::VectorXf mean;                             // 3 per vertex: the mean frame
    std::vector<uint32_t> vertexBlock;                // per vertex, as given
    std::vector<std::vector<uint32_t>> blockVertices; // per block, its vertices ascending
    std::vector<PcaResult> blocks; // per block, over its vertices' 3 rows each (in blockVertices order)
    // Every kept mode, strongest first: (block, column of that block's basis). Singular values
    // descending; ties by block, then column.
    std::vector<std::pair<uint32_t, uint32_t>> modeOrder;
    // [k] = ||Xc - P_k Xc||_F / ||Xc||_F keeping the first k modes of modeOrder, k = 0 .. modes,
    // measured from the projections (so the Eckart–Young identity with the dropped singular
    // values is a real check).
    std::vector<double> relativeErrorPerMode;
};

// samples: 3V x F, rows 3v..3v+2 are vertex v's coordinates in each frame. vertexBlock[v] <
// blockCount; blocks without vertices are allowed (they get no modes). At most
// maxModesPerBlock modes are kept per block. Deterministic for any thread count. Throws
// meadow::Error on empty, non-finite or inconsistent input.
BlockPcaResult computeBlockPca(const Eigen::MatrixXf& samples, const std::vector<uint32_t>& vertexBlock,
                               uint32_t blockCount, uint32_t maxModesPerBlock);

// The smallest k with relativeErrorPerMode[k] <= maxRelativeError (all modes if none is).
uint32_t modesForRelativeError(const BlockPcaResult& pca, double maxRelativeError);

// How many of each block's modes are among the first `modes` of modeOrder.
std::vector<uint32_t> blockRanksForModes(const BlockPcaResult& pca, uint32_t modes);

// The run-time form: per-LOD mode counts from non-increasing totals `lodModes` (lodModes[0]
// modes stored), the basis rows per vertex and the coordinates frame-major.
MotionBasis makeMotionBasis(const BlockPcaResult& pca, const std::array<uint32_t, kLodCount>& lodModes);

} // namespace meadow
