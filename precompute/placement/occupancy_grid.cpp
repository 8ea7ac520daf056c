#include "placement/occupancy_grid.h"

#include "core/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace meadow {

OccupancyGrid::OccupancyGrid(float cellSize, glm::vec2 lo, glm::vec2 hi, int32_t minCellY, int32_t maxCellY,
                             glm::vec2 windDirection)
    : cellSize_(cellSize), minCellY_(minCellY), windDirection_(windDirection), maxCellY_(maxCellY) {
    if (!(cellSize > 0.0f) || !std::isfinite(cellSize))
        throw Error("occupancy grid: cell size " + std::to_string(cellSize) + " m is not a positive finite number");
    if (!std::isfinite(lo.x) || !std::isfinite(lo.y) || !std::isfinite(hi.x) || !std::isfinite(hi.y) ||
        !(lo.x <= hi.x) || !(lo.y <= hi.y))
        throw Error("occupancy grid: the ground rectangle is empty or not finite");
    if (maxCellY < minCellY)
        throw Error("occupancy grid: height range " + std::to_string(minCellY) + " .. " + std::to_string(maxCellY) +
                    " cells is empty");
    horizontalMap(0.0f, true, windDirection); // validates the wind direction
    const double h = double(cellSize);
    origin_ = glm::ivec2(int32_t(std::floor(double(lo.x) / h)), int32_t(std::floor(double(lo.y) / h)));
    const glm::ivec2 last(int32_t(std::floor(double(hi.x) / h)), int32_t(std::floor(double(hi.y) / h)));
    size_ = last - origin_ + glm::ivec2(1);
    const int64_t heightCells = int64_t(maxCellY) - int64_t(minCellY) + 1;
    if (heightCells > int64_t(kMaxWords) * 64)
        throw Error("occupancy grid: " + std::to_string(heightCells) + " cells of height is more than " +
                    std::to_string(kMaxWords * 64) + "; use larger cells");
    words_ = uint32_t((heightCells + 63) / 64);
    bits_.assign(size_t(size_.x) * size_t(size_.y) * words_, 0);
}

template <typename Visit>
bool OccupancyGrid::forEachColumn(const SweptVolume& volume, const InstanceTransform& transform, Visit&& visit) const {
    if (volume.cellSize() != cellSize_)
        throw Error("occupancy grid: a swept volume of cell size " + std::to_string(volume.cellSize()) +
                    " m in a grid of " + std::to_string(cellSize_) + " m");
    if (volume.empty())
        return false;
    const double h = double(cellSize_);
    const double yCells = double(transform.position.y) / h;
    const int32_t shift = int32_t(std::lround(yCells));
    if (!(std::abs(yCells - double(shift)) <= 1e-4))
        throw Error("occupancy grid: an instance at height " + std::to_string(transform.position.y) +
                    " m does not stand on a whole cell");
    if (volume.minCell().y + shift < minCellY_ || volume.maxCell().y + shift > maxCellY_)
        throw Error("occupancy grid: a swept volume spans cells " + std::to_string(volume.minCell().y + shift) +
                    " .. " + std::to_string(volume.maxCell().y + shift) + " in height, outside the grid's " +
                    std::to_string(minCellY_) + " .. " + std::to_string(maxCellY_));

    const glm::dmat2 map = horizontalMap(transform.yaw, transform.mirrored, windDirection_);
    const glm::dvec2 u = map * glm::dvec2(h, 0.0), v = map * glm::dvec2(0.0, h);
    // The turned square's world-aligned bounding half extents, widened against rounding.
    const glm::dvec2 extent = 0.5 * (glm::abs(u) + glm::abs(v)) + glm::dvec2(1e-4 * h);
    const glm::dvec2 base = glm::dvec2(transform.position.x, transform.position.z) - glm::dvec2(origin_) * h;

    std::array<uint64_t, kMaxWords> mask;
    const std::span<const VoxelRun> runs = volume.runs();
    for (const VoxelColumn& column : volume.columns()) {
        const glm::dvec2 centre = base + map * glm::dvec2((double(column.x) + 0.5) * h, (double(column.z) + 0.5) * h);
        // Grid columns c with [c h, (c + 1) h] meeting [centre - extent, centre + extent].
        const int32_t x0 = std::max(0, int32_t(std::ceil((centre.x - extent.x) / h - 1.0)));
        const int32_t x1 = std::min(size_.x - 1, int32_t(std::floor((centre.x + extent.x) / h)));
        const int32_t z0 = std::max(0, int32_t(std::ceil((centre.y - extent.y) / h - 1.0)));
        const int32_t z1 = std::min(size_.y - 1, int32_t(std::floor((centre.y + extent.y) / h)));
        if (x0 > x1 || z0 > z1)
            continue;
        std::fill(mask.begin(), mask.begin() + words_, 0);
        for (uint32_t r = 0; r < column.runCount; ++r) {
            const VoxelRun& run = runs[column.firstRun + r];
            for (int32_t bit = run.y0 + shift - minCellY_; bit <= run.y1 + shift - minCellY_;) {
                const int32_t word = bit / 64, first = bit % 64;
                const int32_t last = std::min(63, run.y1 + shift - minCellY_ - word * 64);
                const uint64_t ones = last - first == 63 ? ~0ull : ((1ull << (last - first + 1)) - 1ull) << first;
                mask[size_t(word)] |= ones;
                bit = word * 64 + last + 1;
            }
        }
        for (int32_t z = z0; z <= z1; ++z)
            for (int32_t x = x0; x <= x1; ++x) {
                const size_t offset = (size_t(z) * size_t(size_.x) + size_t(x)) * words_;
                if (visit(offset, mask))
                    return true;
            }
    }
    return false;
}

void OccupancyGrid::insert(const SweptVolume& volume, const InstanceTransform& transform) {
    forEachColumn(volume, transform, [&](size_t offset, const std::array<uint64_t, kMaxWords>& mask) {
        for (uint32_t w = 0; w < words_; ++w)
            bits_[offset + w] |= mask[w];
        return false;
    });
}

bool OccupancyGrid::overlaps(const SweptVolume& volume, const InstanceTransform& transform) const {
    return forEachColumn(volume, transform, [&](size_t offset, const std::array<uint64_t, kMaxWords>& mask) {
        for (uint32_t w = 0; w < words_; ++w)
            if (bits_[offset + w] & mask[w])
                return true;
        return false;
    });
}

void OccupancyGrid::clear() {
    std::fill(bits_.begin(), bits_.end(), 0);
}

} // namespace meadow
