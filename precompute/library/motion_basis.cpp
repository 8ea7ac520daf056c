#include "library/motion_basis.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>

namespace meadow {

void MotionBasis::finish(const std::string& what) {
    auto fail = [&](const std::string& problem) { return Error(what + ": " + problem); };
    // 64-bit sums: ranks come from files, and a sum that wrapped around could match lodModes while
    // a block's coordinates lie past the end of each frame's.
    uint64_t offset = 0;
    for (size_t b = 0; b < blocks.size(); ++b) {
        const MotionBlock& block = blocks[b];
        if (block.coordOffset != offset)
            throw fail("motion block " + std::to_string(b) + " starts at coordinate " +
                       std::to_string(block.coordOffset) + ", expected " + std::to_string(offset));
        for (uint32_t lod = 1; lod < kLodCount; ++lod)
            if (block.ranks[lod] > block.ranks[lod - 1])
                throw fail("motion block " + std::to_string(b) + " uses more modes at LOD " + std::to_string(lod) +
                           " than at LOD " + std::to_string(lod - 1));
        offset += block.ranks[0];
    }
    for (uint32_t lod = 0; lod < kLodCount; ++lod) {
        uint64_t sum = 0;
        for (const MotionBlock& block : blocks)
            sum += block.ranks[lod];
        if (sum != lodModes[lod])
            throw fail("LOD " + std::to_string(lod) + " counts " + std::to_string(lodModes[lod]) +
                       " motion modes, its blocks " + std::to_string(sum));
    }
    vertexRowOffset.resize(vertexBlock.size());
    size_t rows = 0;
    for (size_t v = 0; v < vertexBlock.size(); ++v) {
        if (vertexBlock[v] >= blocks.size())
            throw fail("vertex " + std::to_string(v) + " names motion block " + std::to_string(vertexBlock[v]) +
                       " of " + std::to_string(blocks.size()));
        vertexRowOffset[v] = uint32_t(rows);
        rows += 3 * size_t(blocks[vertexBlock[v]].ranks[0]);
    }
    if (basis.size() != rows)
        throw fail("the motion basis holds " + std::to_string(basis.size()) + " values, its blocks need " +
                   std::to_string(rows));
    if (coords.size() != size_t(frames) * lodModes[0])
        throw fail("the motion coordinates hold " + std::to_string(coords.size()) + " values for " +
                   std::to_string(frames) + " frames of " + std::to_string(lodModes[0]) + " modes");
    if (relativeErrorPerMode.size() < size_t(lodModes[0]) + 1)
        throw fail("the PCA error table is shorter than the modes stored");
    auto finite = [](float x) { return std::isfinite(x); };
    if (!std::all_of(basis.begin(), basis.end(), finite) || !std::all_of(coords.begin(), coords.end(), finite))
        throw fail("the motion basis or coordinates hold a non-finite value");
}

glm::vec3 MotionBasis::displacement(uint32_t vertex, uint32_t frame, uint32_t lod) const {
    const MotionBlock& block = blocks[vertexBlock[vertex]];
    const float* rows = &basis[vertexRowOffset[vertex]];
    const float* q = &coords[size_t(frame) * lodModes[0] + block.coordOffset];
    glm::vec3 d(0.0f);
    for (uint32_t k = 0; k < block.ranks[lod]; ++k)
        d += glm::vec3(rows[3 * k], rows[3 * k + 1], rows[3 * k + 2]) * q[k];
    return d;
}

uint32_t MotionBasis::maxBlockRank(uint32_t lod) const {
    uint32_t most = 0;
    for (const MotionBlock& block : blocks)
        most = std::max(most, block.ranks[lod]);
    return most;
}

} // namespace meadow
