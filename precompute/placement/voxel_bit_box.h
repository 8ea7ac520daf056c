// Internal to precompute/placement: a dense box of cell flags, the working form of a swept volume
// while it is built (voxelization, dilation, enclosed-space fill). SweptVolume is its compact,
// read-only form. Not part of the public API.
#pragma once

#include "placement/swept_volume.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace meadow {

class VoxelBitBox {
  public:
    // Cells origin .. origin + size - 1, all empty. size components must be positive.
    VoxelBitBox(glm::ivec3 origin, glm::ivec3 size);
    // The volume's cells in a box grown by `pad` cells on every side.
    static VoxelBitBox fromVolume(const SweptVolume& volume, int32_t pad);

    glm::ivec3 origin() const { return origin_; }
    glm::ivec3 size() const { return size_; }
    bool inside(glm::ivec3 cell) const {
        const glm::ivec3 local = cell - origin_;
        return local.x >= 0 && local.y >= 0 && local.z >= 0 && local.x < size_.x && local.y < size_.y &&
               local.z < size_.z;
    }
    // y is the fastest axis, so a column's cells are contiguous.
    size_t offset(glm::ivec3 cell) const {
        const glm::ivec3 local = cell - origin_;
        return (size_t(local.z) * size_t(size_.x) + size_t(local.x)) * size_t(size_.y) + size_t(local.y);
    }
    void set(glm::ivec3 cell) { flags_[offset(cell)] = 1; }
    bool test(glm::ivec3 cell) const { return flags_[offset(cell)] != 0; }
    // Cell-wise OR with a box of the same origin and size (order-independent, so parallel
    // voxelization reduces to the same bits for any thread count).
    void orWith(const VoxelBitBox& other);

    // Every cell within k cells along each axis of a set cell, in place (the box must already have
    // k cells of free border). Separable: three 1D max filters.
    void dilate(int32_t k);
    // Sets the empty cells with y >= 0 that no face-connected path of empty cells with y >= 0
    // joins to the box's border: the space enclosed between a surface and the ground plane.
    void fillEnclosedAboveGround();

    // The compact form; an error (meadow::Error) when no cell is set.
    SweptVolume toVolume(float cellSize) const;

  private:
    glm::ivec3 origin_;
    glm::ivec3 size_;
    std::vector<uint8_t> flags_;
};

} // namespace meadow
