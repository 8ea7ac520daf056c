// First-fit allocator of ranges inside one block: the CPU-only core of meadow's Vulkan memory
// sub-allocator (vk/memory.h), kept separate so it is unit-tested without a device.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace meadow {

class RangeAllocator {
  public:
    explicit RangeAllocator(uint64_t size);

    // Offset of a new range of `size` bytes aligned to `alignment` (a power of two), or nothing
    // if no free range is large enough.
    std::optional<uint64_t> allocate(uint64_t size, uint64_t alignment);
    // Returns a range given out by allocate(); neighbouring free ranges merge.
    void free(uint64_t offset, uint64_t size);

    uint64_t size() const { return size_; }
    uint64_t freeBytes() const;
    bool empty() const { return freeBytes() == size_; }
    size_t freeRangeCount() const { return free_.size(); }

  private:
    struct Range {
        uint64_t offset;
        uint64_t size;
    };
    uint64_t size_;
    std::vector<Range> free_; // sorted by offset, never adjacent
};

} // namespace meadow
