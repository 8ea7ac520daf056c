// A clump's reduced motion as the library stores it and the run time plays it
// (docs/ARCHITECTURE.md, Motion): x_v(t) = x̄_v + sum over k < rank of U_v,k q_k(t), where the
// modes are those of the rod the vertex follows (motion/block_pca.h). Each level of detail keeps a
// prefix of every rod's modes.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace meadow {

inline constexpr uint32_t kLodCount = 5;

struct MotionBlock {
    uint32_t coordOffset = 0;                // where this block's coordinates start in a frame's q
    std::array<uint32_t, kLodCount> ranks{}; // modes used at each LOD, non-increasing; ranks[0] stored
};

struct MotionBasis {
    uint32_t frames = 0;
    std::array<uint32_t, kLodCount> lodModes{}; // modes over all blocks per LOD; lodModes[0] = coords per frame
    std::vector<uint32_t> vertexBlock;          // per vertex
    std::vector<MotionBlock> blocks;
    std::vector<float> basis;                 // per vertex in order: ranks[0] of its block x (x, y, z)
    std::vector<float> coords;                // frame-major: frames x lodModes[0]
    std::vector<double> relativeErrorPerMode; // [k], k = 0 .. all modes the PCA found (not only those stored)
    std::vector<uint32_t> vertexRowOffset;    // derived (finish()): index into basis of vertex v's first mode

    uint32_t modesPerFrame() const { return lodModes[0]; }
    // Computes vertexRowOffset and checks every size and offset; throws meadow::Error naming
    // `what` on an inconsistency (a corrupt library).
    void finish(const std::string& what);
    // The displacement from the mean of vertex v at a frame, using the LOD's modes.
    glm::vec3 displacement(uint32_t vertex, uint32_t frame, uint32_t lod = 0) const;
    // The most modes any vertex uses at a LOD (its run-time cost).
    uint32_t maxBlockRank(uint32_t lod) const;
};

} // namespace meadow
