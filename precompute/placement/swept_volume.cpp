#include "placement/swept_volume.h"

#include "core/error.h"
#include "placement/voxel_bit_box.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace meadow {
namespace {

void checkCellSize(float cellSize) {
    if (!(cellSize > 0.0f) || !std::isfinite(cellSize))
        throw Error("swept volume: cell size " + std::to_string(cellSize) + " m is not a positive finite number");
}

// Farthest horizontal distance from the axis of any point of column (x, z)'s cells.
double columnReach(int32_t x, int32_t z, double cellSize) {
    const double fx = std::max(std::abs(double(x)), std::abs(double(x) + 1.0)) * cellSize;
    const double fz = std::max(std::abs(double(z)), std::abs(double(z) + 1.0)) * cellSize;
    return std::sqrt(fx * fx + fz * fz);
}

} // namespace

// ---- VoxelBitBox --------------------------------------------------------------------------------

VoxelBitBox::VoxelBitBox(glm::ivec3 origin, glm::ivec3 size)
    : origin_(origin), size_(size), flags_(size_t(size.x) * size_t(size.y) * size_t(size.z), 0) {}

VoxelBitBox VoxelBitBox::fromVolume(const SweptVolume& volume, int32_t pad) {
    VoxelBitBox box(volume.minCell() - glm::ivec3(pad), volume.maxCell() - volume.minCell() + glm::ivec3(1 + 2 * pad));
    for (const VoxelColumn& column : volume.columns())
        for (uint32_t r = 0; r < column.runCount; ++r) {
            const VoxelRun& run = volume.runs()[column.firstRun + r];
            for (int32_t y = run.y0; y <= run.y1; ++y)
                box.set({column.x, y, column.z});
        }
    return box;
}

void VoxelBitBox::orWith(const VoxelBitBox& other) {
    for (size_t i = 0; i < flags_.size(); ++i)
        flags_[i] |= other.flags_[i];
}

void VoxelBitBox::dilate(int32_t k) {
    if (k <= 0)
        return;
    // One 1D max filter per axis: out[i] = OR of in[i-k .. i+k], by a sliding count of set cells.
    std::vector<uint8_t> line;
    for (int axis = 0; axis < 3; ++axis) {
        const int32_t length = size_[axis];
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        line.resize(size_t(length));
        for (int32_t u = 0; u < size_[a1]; ++u)
            for (int32_t v = 0; v < size_[a2]; ++v) {
                glm::ivec3 cell = origin_;
                cell[a1] += u;
                cell[a2] += v;
                for (int32_t i = 0; i < length; ++i) {
                    cell[axis] = origin_[axis] + i;
                    line[size_t(i)] = flags_[offset(cell)];
                }
                int32_t count = 0;
                for (int32_t i = 0; i < std::min(k, length); ++i)
                    count += line[size_t(i)];
                for (int32_t i = 0; i < length; ++i) {
                    if (i + k < length)
                        count += line[size_t(i + k)];
                    if (i - k - 1 >= 0)
                        count -= line[size_t(i - k - 1)];
                    cell[axis] = origin_[axis] + i;
                    flags_[offset(cell)] = count > 0 ? 1 : 0;
                }
            }
    }
}

void VoxelBitBox::fillEnclosedAboveGround() {
    // Flood the outside from the box's sides and top through face-connected empty cells above
    // ground; the ground (y < 0) is a wall. What the flood never reaches is enclosed.
    std::vector<uint8_t> outside(flags_.size(), 0);
    std::vector<glm::ivec3> stack;
    const glm::ivec3 last = origin_ + size_ - glm::ivec3(1);
    auto visit = [&](glm::ivec3 cell) {
        if (!inside(cell) || cell.y < 0)
            return;
        const size_t i = offset(cell);
        if (flags_[i] || outside[i])
            return;
        outside[i] = 1;
        stack.push_back(cell);
    };
    for (int32_t z = origin_.z; z <= last.z; ++z)
        for (int32_t x = origin_.x; x <= last.x; ++x)
            for (int32_t y = std::max(origin_.y, 0); y <= last.y; ++y)
                if (x == origin_.x || x == last.x || z == origin_.z || z == last.z || y == last.y)
                    visit({x, y, z});
    while (!stack.empty()) {
        const glm::ivec3 cell = stack.back();
        stack.pop_back();
        for (int axis = 0; axis < 3; ++axis)
            for (int32_t step : {-1, 1}) {
                glm::ivec3 next = cell;
                next[axis] += step;
                visit(next);
            }
    }
    for (int32_t z = origin_.z; z <= last.z; ++z)
        for (int32_t x = origin_.x; x <= last.x; ++x)
            for (int32_t y = std::max(origin_.y, 0); y <= last.y; ++y) {
                const size_t i = offset({x, y, z});
                if (!outside[i])
                    flags_[i] = 1;
            }
}

SweptVolume VoxelBitBox::toVolume(float cellSize) const {
    SweptVolume volume;
    volume.cellSize_ = cellSize;
    glm::ivec3 lo(std::numeric_limits<int32_t>::max()), hi(std::numeric_limits<int32_t>::min());
    double reach = 0.0;
    for (int32_t z = 0; z < size_.z; ++z)
        for (int32_t x = 0; x < size_.x; ++x) {
            const glm::ivec3 base = origin_ + glm::ivec3(x, 0, z);
            const uint8_t* column = flags_.data() + offset(base);
            VoxelColumn out{base.x, base.z, uint32_t(volume.runs_.size()), 0};
            for (int32_t y = 0; y < size_.y; ++y) {
                if (!column[y])
                    continue;
                const int32_t y0 = y;
                while (y + 1 < size_.y && column[y + 1])
                    ++y;
                volume.runs_.push_back({origin_.y + y0, origin_.y + y});
                volume.voxelCount_ += size_t(y - y0 + 1);
                ++out.runCount;
            }
            if (out.runCount == 0)
                continue;
            lo = glm::min(lo, glm::ivec3(base.x, volume.runs_[out.firstRun].y0, base.z));
            hi = glm::max(hi, glm::ivec3(base.x, volume.runs_.back().y1, base.z));
            reach = std::max(reach, columnReach(base.x, base.z, double(cellSize)));
            volume.columns_.push_back(out);
        }
    if (volume.voxelCount_ == 0)
        throw Error("swept volume: no cell is occupied");
    volume.minCell_ = lo;
    volume.maxCell_ = hi;
    // Rounded up so the float radius still holds every cell.
    volume.footprintRadius_ = std::nextafter(float(reach), std::numeric_limits<float>::infinity());
    const glm::ivec3 extent = hi - lo + glm::ivec3(1);
    volume.columnIndex_.assign(size_t(extent.x) * size_t(extent.z), -1);
    for (size_t c = 0; c < volume.columns_.size(); ++c) {
        const VoxelColumn& column = volume.columns_[c];
        volume.columnIndex_[size_t(column.z - lo.z) * size_t(extent.x) + size_t(column.x - lo.x)] = int32_t(c);
    }
    return volume;
}

// ---- SweptVolume ---------------------------------------------------------------------------------

SweptVolume SweptVolume::fromCells(float cellSize, std::span<const glm::ivec3> cells) {
    checkCellSize(cellSize);
    if (cells.empty())
        throw Error("swept volume: no cell given");
    glm::ivec3 lo = cells[0], hi = cells[0];
    for (const glm::ivec3& cell : cells) {
        lo = glm::min(lo, cell);
        hi = glm::max(hi, cell);
    }
    VoxelBitBox box(lo, hi - lo + glm::ivec3(1));
    for (const glm::ivec3& cell : cells)
        box.set(cell);
    return box.toVolume(cellSize);
}

SweptVolume SweptVolume::fromImplicit(float cellSize, glm::vec3 lo, glm::vec3 hi,
                                      const std::function<bool(const glm::vec3& centre)>& inside) {
    checkCellSize(cellSize);
    for (int axis = 0; axis < 3; ++axis)
        if (!std::isfinite(lo[axis]) || !std::isfinite(hi[axis]) || !(lo[axis] <= hi[axis]))
            throw Error("swept volume: implicit shape box is empty or not finite");
    // Cells whose centres (i + 1/2) h lie in [lo, hi].
    const glm::ivec3 first(glm::ceil(lo / cellSize - 0.5f)), last(glm::floor(hi / cellSize - 0.5f));
    if (glm::any(glm::lessThan(last, first)))
        throw Error("swept volume: implicit shape box holds no cell centre");
    VoxelBitBox box(first, last - first + glm::ivec3(1));
    bool any = false;
    for (int32_t z = first.z; z <= last.z; ++z)
        for (int32_t x = first.x; x <= last.x; ++x)
            for (int32_t y = first.y; y <= last.y; ++y)
                if (inside((glm::vec3(x, y, z) + 0.5f) * cellSize)) {
                    box.set({x, y, z});
                    any = true;
                }
    if (!any)
        throw Error("swept volume: the implicit shape contains no cell centre");
    return box.toVolume(cellSize);
}

std::span<const VoxelRun> SweptVolume::columnRuns(int32_t x, int32_t z) const {
    if (empty() || x < minCell_.x || x > maxCell_.x || z < minCell_.z || z > maxCell_.z)
        return {};
    const int32_t width = maxCell_.x - minCell_.x + 1;
    const int32_t c = columnIndex_[size_t(z - minCell_.z) * size_t(width) + size_t(x - minCell_.x)];
    if (c < 0)
        return {};
    const VoxelColumn& column = columns_[size_t(c)];
    return {runs_.data() + column.firstRun, column.runCount};
}

bool SweptVolume::contains(glm::ivec3 cell) const {
    for (const VoxelRun& run : columnRuns(cell.x, cell.z))
        if (cell.y >= run.y0 && cell.y <= run.y1)
            return true;
    return false;
}

std::vector<glm::ivec3> SweptVolume::cells() const {
    std::vector<glm::ivec3> out;
    out.reserve(voxelCount_);
    for (const VoxelColumn& column : columns_)
        for (uint32_t r = 0; r < column.runCount; ++r)
            for (int32_t y = runs_[column.firstRun + r].y0; y <= runs_[column.firstRun + r].y1; ++y)
                out.push_back({column.x, y, column.z});
    return out;
}

SweptVolume SweptVolume::dilated(float margin) const {
    if (!(margin >= 0.0f) || !std::isfinite(margin))
        throw Error("swept volume: dilation margin " + std::to_string(margin) + " m is not a finite number >= 0");
    if (empty())
        throw Error("swept volume: cannot dilate an empty volume");
    const int32_t k = int32_t(std::ceil(double(margin) / double(cellSize_) - 1e-4));
    if (k <= 0)
        return *this;
    VoxelBitBox box = VoxelBitBox::fromVolume(*this, k);
    box.dilate(k);
    return box.toVolume(cellSize_);
}

bool SweptVolume::operator==(const SweptVolume& other) const {
    if (cellSize_ != other.cellSize_ || voxelCount_ != other.voxelCount_ || minCell_ != other.minCell_ ||
        maxCell_ != other.maxCell_ || columns_.size() != other.columns_.size() || runs_.size() != other.runs_.size())
        return false;
    for (size_t i = 0; i < columns_.size(); ++i)
        if (columns_[i].x != other.columns_[i].x || columns_[i].z != other.columns_[i].z ||
            columns_[i].runCount != other.columns_[i].runCount)
            return false;
    for (size_t i = 0; i < runs_.size(); ++i)
        if (runs_[i].y0 != other.runs_[i].y0 || runs_[i].y1 != other.runs_[i].y1)
            return false;
    return true;
}

} // namespace meadow
