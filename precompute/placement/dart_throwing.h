// Internal to precompute/placement: what the voxel fill (tile_fill.cpp) and the Poisson-disc
// baseline (poisson_disc.cpp) share, so that both throw exactly the same darts under exactly the
// same neighbour rules and budgets. Not part of the public API.
#pragma once

#include "core/random.h"
#include "placement/tile_fill.h"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace meadow {

enum class DartKind : uint32_t { Clump = 0, Rock = 1 };

// The darts of one tile and kind, in order: position uniform in the tile, volume index uniform,
// yaw uniform in [-jitter, jitter] (clumps) or [0, 2 pi) (rocks), mirror a fair coin when allowed.
class DartStream {
  public:
    DartStream(const TileFillParams& params, uint32_t tile, DartKind kind, uint32_t volumeCount);
    TilePlacement next();

  private:
    Random random_;
    float tileSize_;
    float yawLo_, yawHi_;
    bool mirror_;
    uint32_t volumeCount_;
};

// Offsets (in tiles) at which tile `u` can stand relative to tile `t` in a tiling from the
// complete set: (0, 0) when u == t (its own instances), the edge offsets whose colours match, and
// the four corners.
std::vector<glm::ivec2> neighbourOffsets(uint32_t t, uint32_t u);

// Throws meadow::Error for bad params (see fillWangTiles): `what` names the caller, maxRadius is
// the largest footprint radius, cellSize the grid's (0 for discs, which need no grid).
void checkTileFillParams(const TileFillParams& params, float maxRadius, float cellSize, const std::string& what);

// Whether a disc of radius r at (x, z) in tile coordinates can reach the square [lo, hi]^2.
inline bool discReaches(glm::vec2 centre, float radius, float lo, float hi) {
    const glm::vec2 nearest = glm::clamp(centre, glm::vec2(lo), glm::vec2(hi));
    const glm::vec2 d = centre - nearest;
    return glm::dot(d, d) <= radius * radius;
}

// Whether the dart budget is spent: too many darts or too many rejections in a row.
inline bool budgetSpent(const TileFillParams& params, uint32_t darts, uint32_t failures) {
    return darts >= params.maxDarts || failures >= params.maxConsecutiveFailures;
}

} // namespace meadow
