// The order in which the near raster's two passes' workgroups take the draws of their list
// (shaders/shared/work_order.h; the splat pass keeps the cull pass's order): a permutation of the
// list, which hands any contiguous run of workgroups (lavapipe gives each of its threads one)
// entries from all over the list.
#include "work_order.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

using namespace meadow;

namespace {

// Every entry taken exactly once.
void expectPermutation(uint32_t count) {
    const uint32_t stride = gpu::workStride(count);
    std::vector<uint8_t> taken(count, 0);
    for (uint32_t slot = 0; slot < count; ++slot) {
        const uint32_t entry = gpu::workEntry(slot, count, stride);
        ASSERT_LT(entry, count) << "count " << count << ", slot " << slot;
        ASSERT_EQ(taken[entry], 0) << "count " << count << ": entry " << entry << " taken twice";
        taken[entry] = 1;
    }
}

} // namespace

TEST(WorkOrder, IsAPermutationOfTheList) {
    for (uint32_t count = 1; count <= 3000; ++count)
        expectPermutation(count);
    for (uint32_t count : {65535u, 65536u, 1000000u, 1048576u, 2097152u})
        expectPermutation(count);
}

TEST(WorkOrder, StrideIsCoprimeAndNearTheGoldenSection) {
    for (uint32_t count = 3; count <= 100000; count += 7) {
        const uint32_t stride = gpu::workStride(count);
        EXPECT_EQ(std::gcd(count, stride), 1u) << count;
        EXPECT_NEAR(double(stride), 0.618 * count, 0.01 * count + 3.0) << count;
    }
    // Near the top of the range the products need 64 bits.
    const uint32_t big = 4000000000u;
    const uint32_t stride = gpu::workStride(big);
    EXPECT_EQ(std::gcd(big, stride), 1u);
    EXPECT_LT(gpu::workEntry(big - 1u, big, stride), big);
}

// lavapipe hands each of its T threads a contiguous run of the dispatch's workgroups. Where the
// costly entries bunch up in one quarter of the list (the clumps nearest the eye, appended together
// by the cull pass), every thread must still get about its share of that quarter: in the list's
// own order the first thread would get all of it or none.
TEST(WorkOrder, ContiguousRunsOfSlotsTakeEntriesFromEveryPartOfTheList) {
    for (uint32_t count = 16; count <= 3000; ++count) {
        const uint32_t stride = gpu::workStride(count);
        for (uint32_t threads : {2u, 3u, 4u, 8u, 16u})
            for (uint32_t quarter = 0; quarter < 4; ++quarter) {
                const uint32_t lo = quarter * count / 4, hi = (quarter + 1) * count / 4;
                const double share = double(hi - lo) / threads;
                for (uint32_t t = 0; t < threads; ++t) {
                    uint32_t inQuarter = 0;
                    for (uint32_t slot = t * count / threads; slot < (t + 1) * count / threads; ++slot) {
                        const uint32_t entry = gpu::workEntry(slot, count, stride);
                        inQuarter += entry >= lo && entry < hi;
                    }
                    EXPECT_NEAR(double(inQuarter), share, 3.0 + 0.2 * share)
                        << count << " entries, thread " << t << " of " << threads << ", quarter " << quarter;
                }
            }
    }
}
