// A world-aligned grid of occupied cells over a rectangle of ground: the fast overlap test behind
// dart throwing (tile_fill.h). Placed swept volumes are rasterised into it, and a candidate is
// tested against everything rasterised so far in one pass over its own columns, whatever the
// number of neighbours.
//
// Conservative under rotation: a placed volume's column (a square of side h turned by the
// instance's yaw and mirror) is widened to its world-axis-aligned bounding square, plus 1e-4 of a
// cell, and every grid column that bounding square touches (closed) receives the column's height
// bits. A candidate's columns are widened the same way. If two surfaces truly touch at a point p,
// p lies in an occupied closed cell of each volume, hence inside both widened squares at a height
// both bit masks hold; the grid column containing p (either one, if p is on a boundary) is then
// written by the first and read by the second. So the grid never misses an overlap that
// sweptVolumesOverlap (instance.h) reports; it may report a little more (the widening is at most
// (sqrt(2) - 1) h / 2 per side at 45 degrees, plus the grid's own quantisation).
//
// Heights: the grid holds cells minCellY .. maxCellY of the world grid whose cell boundaries are
// at y = j h; instances must stand at a whole number of cells (y = 0 on a flat tile).
#pragma once

#include "placement/instance.h"
#include "placement/swept_volume.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace meadow {

class OccupancyGrid {
  public:
    // Columns covering the ground rectangle [lo, hi] (x, z) at cell size h, their corners on the
    // world lattice (multiples of h); heights minCellY .. maxCellY. Throws meadow::Error on a bad
    // cell size, an empty or non-finite rectangle, maxCellY < minCellY or more than kMaxWords words
    // per column.
    OccupancyGrid(float cellSize, glm::vec2 lo, glm::vec2 hi, int32_t minCellY, int32_t maxCellY,
                  glm::vec2 windDirection);

    // Adds the placed volume. Parts outside the rectangle are dropped: the caller makes the
    // rectangle cover every place a tested candidate can reach. Throws meadow::Error when the
    // volume's cell size differs, the instance does not stand at a whole number of cells, or its
    // cells leave the grid's height range.
    void insert(const SweptVolume& volume, const InstanceTransform& transform);
    // True when the placed volume may meet anything inserted (never false when
    // sweptVolumesOverlap is true for some inserted instance). Same errors as insert.
    bool overlaps(const SweptVolume& volume, const InstanceTransform& transform) const;
    void clear();

    float cellSize() const { return cellSize_; }

    // Heights held per column, at most: 64 words of 64 cells (25 m at 2.5 cm cells).
    static constexpr uint32_t kMaxWords = 64;

  private:
    // Calls visit(gridColumnWords, columnMask) for every grid column each of the volume's columns
    // reaches; stops and returns true as soon as visit does.
    template <typename Visit> bool forEachColumn(const SweptVolume&, const InstanceTransform&, Visit&&) const;

    float cellSize_;
    glm::ivec2 origin_; // grid column (0, 0) is world column origin_
    glm::ivec2 size_;
    int32_t minCellY_;
    uint32_t words_; // 64-bit words per column
    glm::vec2 windDirection_;
    int32_t maxCellY_;
    std::vector<uint64_t> bits_; // words_ per column, columns in (z, x) order
};

} // namespace meadow
