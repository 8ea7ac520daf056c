#include "vk/range_allocator.h"

#include <algorithm>
#include <cassert>

namespace meadow {

RangeAllocator::RangeAllocator(uint64_t size) : size_(size) {
    if (size > 0)
        free_.push_back({0, size});
}

std::optional<uint64_t> RangeAllocator::allocate(uint64_t size, uint64_t alignment) {
    assert(alignment > 0 && (alignment & (alignment - 1)) == 0);
    if (size == 0)
        size = 1;
    for (size_t i = 0; i < free_.size(); ++i) {
        Range r = free_[i];
        uint64_t start = (r.offset + alignment - 1) & ~(alignment - 1);
        if (start + size > r.offset + r.size)
            continue;
        // Split the free range into what lies before the allocation and what lies after it.
        uint64_t before = start - r.offset;
        uint64_t afterOffset = start + size;
        uint64_t after = r.offset + r.size - afterOffset;
        free_.erase(free_.begin() + static_cast<std::ptrdiff_t>(i));
        if (after > 0)
            free_.insert(free_.begin() + static_cast<std::ptrdiff_t>(i), {afterOffset, after});
        if (before > 0)
            free_.insert(free_.begin() + static_cast<std::ptrdiff_t>(i), {r.offset, before});
        return start;
    }
    return std::nullopt;
}

void RangeAllocator::free(uint64_t offset, uint64_t size) {
    if (size == 0)
        size = 1;
    assert(offset + size <= size_);
    auto it =
        std::lower_bound(free_.begin(), free_.end(), offset, [](const Range& r, uint64_t o) { return r.offset < o; });
    it = free_.insert(it, {offset, size});
    // Merge with the next range, then with the previous one.
    if (it + 1 != free_.end() && it->offset + it->size == (it + 1)->offset) {
        it->size += (it + 1)->size;
        free_.erase(it + 1);
    }
    if (it != free_.begin() && (it - 1)->offset + (it - 1)->size == it->offset) {
        (it - 1)->size += it->size;
        free_.erase(it);
    }
}

uint64_t RangeAllocator::freeBytes() const {
    uint64_t total = 0;
    for (const Range& r : free_)
        total += r.size;
    return total;
}

} // namespace meadow
