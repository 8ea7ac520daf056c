// Swept volumes (docs/ARCHITECTURE.md, Placement; Cove & James 2004, section 2.2): the set of cells
// of a uniform grid that a clump's surface touches in any of its simulated frames. Placement tests
// these sets for overlap instead of discs of the swept radius, so clumps whose shapes interleave
// can stand closer.
//
// Grid and units: metres, clump space (y up, the rhizome at the origin, the ground the plane
// y = 0). Cell (i, j, k) is the closed box [i h, (i+1) h] x [j h, (j+1) h] x [k h, (k+1) h] for
// cell size h, so cell boundaries pass through the clump origin and a y = 0 ground lies on a cell
// boundary. Closed boxes matter: a surface point on a shared face marks every cell that contains
// it, which is what makes overlap tests between differently placed grids conservative
// (instance.h).
//
// Storage: the occupied cells of each vertical column (i, k) as runs of consecutive j, columns in
// (k, i) order, plus a dense column index over the bounding box. A few thousand columns and runs
// per clump; a run-length column also answers overlap at any real-valued height offset.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace meadow {

// Occupied cells j0..j1 (inclusive) of one column.
struct VoxelRun {
    int32_t y0 = 0;
    int32_t y1 = 0;
};

// A non-empty column (i = x, k = z) and its runs runs()[firstRun .. firstRun + runCount).
struct VoxelColumn {
    int32_t x = 0;
    int32_t z = 0;
    uint32_t firstRun = 0;
    uint32_t runCount = 0;
};

class SweptVolume {
  public:
    SweptVolume() = default;

    // The volume made of exactly these cells (any order, duplicates allowed). Throws meadow::Error
    // if the cell size is not a positive finite number or no cell is given.
    static SweptVolume fromCells(float cellSize, std::span<const glm::ivec3> cells);

    // A synthetic volume for tests and simple obstacles: every cell of the grid inside the box
    // [lo, hi] whose centre satisfies `inside`. Throws meadow::Error on a bad cell size or box, or
    // when no cell is inside.
    static SweptVolume fromImplicit(float cellSize, glm::vec3 lo, glm::vec3 hi,
                                    const std::function<bool(const glm::vec3& centre)>& inside);

    float cellSize() const { return cellSize_; }
    bool empty() const { return voxelCount_ == 0; }
    size_t voxelCount() const { return voxelCount_; }
    glm::ivec3 minCell() const { return minCell_; } // inclusive bounds of the occupied cells
    glm::ivec3 maxCell() const { return maxCell_; }

    // Max horizontal distance from the clump axis (x = z = 0) of any point of any occupied cell:
    // the radius of the smallest axis-centred cylinder that holds the volume under any yaw.
    float footprintRadius() const { return footprintRadius_; }
    // Height range of the occupied cells (m): minCell().y * h and (maxCell().y + 1) * h.
    float minY() const { return float(minCell_.y) * cellSize_; }
    float maxY() const { return float(maxCell_.y + 1) * cellSize_; }

    bool contains(glm::ivec3 cell) const;
    // The runs of column (x, z); empty when the column holds nothing.
    std::span<const VoxelRun> columnRuns(int32_t x, int32_t z) const;
    std::span<const VoxelColumn> columns() const { return columns_; }
    std::span<const VoxelRun> runs() const { return runs_; }
    // Every occupied cell, sorted by (z, x, y).
    std::vector<glm::ivec3> cells() const;

    // This volume grown by `margin` metres, rounded up to whole cells k (a margin within 1e-4 of a
    // cell of a whole number counts as that number): every cell within k cells along each axis of
    // an occupied cell (a (2k+1)^3 cube, which holds the ball of radius k h). Throws meadow::Error
    // for a negative or non-finite margin.
    SweptVolume dilated(float margin) const;

    // Both volumes hold exactly the same cells at the same cell size.
    bool operator==(const SweptVolume& other) const;

  private:
    friend class VoxelBitBox;
    float cellSize_ = 0.0f;
    glm::ivec3 minCell_{0};
    glm::ivec3 maxCell_{-1};
    size_t voxelCount_ = 0;
    float footprintRadius_ = 0.0f;
    std::vector<VoxelColumn> columns_;
    std::vector<VoxelRun> runs_;
    std::vector<int32_t> columnIndex_; // dense (x, z) over the bounding box: index into columns_ or -1
};

// Surface voxelization options.
struct VoxelizeParams {
    float cellSize = 0.025f; // h (m), a few cm
    float margin = 0.0f;     // safety dilation (m), rounded up to whole cells
    // Also mark the cells enclosed between the surface and the ground plane y = 0 (for closed-by-
    // the-ground shapes such as half-buried rocks, so nothing can be placed inside them). Found by
    // flood fill from outside through face-connected empty cells above ground: a conservative
    // surface voxelization separates face-connected paths, so the fill cannot leak inside.
    bool fillEnclosed = false;
};

// Writes frame `frame` (0-based) of the clump's vertex positions (clump space) into `positions`,
// resized as needed. Called from several threads at once, twice per frame (bounds, then cells):
// it must be thread-safe and return the same positions for the same frame every time.
using FrameSource = std::function<void(uint32_t frame, std::vector<glm::vec3>& positions)>;

// The swept volume of a triangle mesh over `frameCount` frames: every cell whose closed box any
// frame's triangle touches (triangle/box overlap by the separating axis test of Akenine-Möller
// 2001, so thin blades and slivers never slip between cells), then dilated by params.margin. Which
// frames to pass (e.g. many from the strongest wind level, as Cove & James 2004 weight theirs) is
// the caller's choice; see selectSweptFrames. Runs on all cores; the result is the same for any
// thread count. Throws meadow::Error on bad parameters, an index out of range, an index count not
// a multiple of 3, no triangles, no frames, or a position that is not finite.
SweptVolume voxelizeSweptSurface(std::span<const uint32_t> indices, uint32_t frameCount, const FrameSource& frameAt,
                                 const VoxelizeParams& params);

// The same, for frames held in memory (each frame one position per vertex).
SweptVolume voxelizeSweptSurface(std::span<const uint32_t> indices, std::span<const std::vector<glm::vec3>> frames,
                                 const VoxelizeParams& params);

// A frame subset for voxelization: `budget` frame numbers, with `strongestShare` of them spread
// evenly over the last (strongest) level and the rest spread evenly over all other levels, so
// the swept volume leans toward the strongest wind as Cove & James 2004 weight theirs. Frames are
// numbered through the levels in order (level 0's first, then level 1's, ...). Returns sorted,
// distinct frame numbers (fewer than `budget` when the levels hold fewer frames). Throws
// meadow::Error when there is no level, a level has no frame, or strongestShare is outside [0, 1].
std::vector<uint32_t> selectSweptFrames(std::span<const uint32_t> framesPerLevel, uint32_t budget,
                                        float strongestShare);

} // namespace meadow
