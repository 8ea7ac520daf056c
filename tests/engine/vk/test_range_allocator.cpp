#include "vk/range_allocator.h"

#include <gtest/gtest.h>

using meadow::RangeAllocator;

TEST(RangeAllocator, AlignsAndFillsFirstFit) {
    RangeAllocator a(1024);
    auto x = a.allocate(100, 1);
    auto y = a.allocate(10, 256);
    ASSERT_TRUE(x && y);
    EXPECT_EQ(*x, 0u);
    EXPECT_EQ(*y, 256u); // aligned up past the first range
    // The gap [100, 256) is still free and is used first by a small request.
    auto z = a.allocate(50, 4);
    ASSERT_TRUE(z);
    EXPECT_EQ(*z, 100u);
    EXPECT_EQ(a.freeBytes(), 1024u - 100 - 10 - 50);
}

TEST(RangeAllocator, RefusesWhatDoesNotFit) {
    RangeAllocator a(256);
    EXPECT_FALSE(a.allocate(257, 1));
    ASSERT_TRUE(a.allocate(200, 1));
    EXPECT_FALSE(a.allocate(100, 1));
    // 56 bytes remain, but not at a 64-byte aligned offset with room for 56.
    EXPECT_FALSE(a.allocate(56, 64));
    EXPECT_TRUE(a.allocate(56, 8));
}

TEST(RangeAllocator, FreeMergesNeighbours) {
    RangeAllocator a(300);
    auto x = a.allocate(100, 1), y = a.allocate(100, 1), z = a.allocate(100, 1);
    ASSERT_TRUE(x && y && z);
    EXPECT_EQ(a.freeBytes(), 0u);
    a.free(*x, 100);
    a.free(*z, 100);
    EXPECT_EQ(a.freeRangeCount(), 2u);
    a.free(*y, 100); // joins both neighbours into one range
    EXPECT_EQ(a.freeRangeCount(), 1u);
    EXPECT_TRUE(a.empty());
    auto all = a.allocate(300, 1);
    ASSERT_TRUE(all);
    EXPECT_EQ(*all, 0u);
}

TEST(RangeAllocator, RandomChurnNeverOverlaps) {
    RangeAllocator a(1 << 16);
    struct Live {
        uint64_t offset, size;
    };
    std::vector<Live> live;
    uint64_t state = 12345;
    auto next = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return state >> 33;
    };
    for (int step = 0; step < 5000; ++step) {
        if (!live.empty() && next() % 2 == 0) {
            size_t i = next() % live.size();
            a.free(live[i].offset, live[i].size);
            live.erase(live.begin() + long(i));
            continue;
        }
        uint64_t size = 1 + next() % 700, align = 1ull << (next() % 8);
        if (auto off = a.allocate(size, align)) {
            EXPECT_EQ(*off % align, 0u);
            for (const Live& l : live)
                ASSERT_TRUE(*off + size <= l.offset || l.offset + l.size <= *off) << "overlap at step " << step;
            live.push_back({*off, size});
        }
    }
    for (const Live& l : live)
        a.free(l.offset, l.size);
    EXPECT_TRUE(a.empty());
    EXPECT_EQ(a.freeRangeCount(), 1u);
}
