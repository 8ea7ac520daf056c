// checkDrawRanges (render/draw_ranges.h): a draw that reads outside a buffer is named.
#include "render/draw_ranges.h"

#include <gtest/gtest.h>

using namespace meadow;

namespace {
// Two draws of one triangle each over 6 LOD vertices; visible ranges 0..4 and 4..10.
struct Fixture {
    std::vector<uint32_t> indices{0, 1, 2, 0, 1, 2};
    std::vector<uint32_t> capacity{4, 6};
    std::vector<gpu::GpuDrawIndexedCommand> draws{{3, 4, 0, 0, 0}, {3, 6, 3, 3, 4}};
    std::vector<std::string> check(uint64_t lodVertices = 6, uint64_t visible = 10) const {
        return checkDrawRanges(draws, {indices, lodVertices, visible, capacity});
    }
};
bool mentions(const std::vector<std::string>& problems, const std::string& text) {
    for (const std::string& p : problems)
        if (p.find(text) != std::string::npos)
            return true;
    return false;
}
} // namespace

TEST(DrawRanges, RangesThatFitPass) {
    EXPECT_TRUE(Fixture().check().empty());
}

TEST(DrawRanges, EachKindOfOverrunIsNamed) {
    Fixture f;
    f.draws[1].firstIndex = 4; // indices 4..7 of 6
    EXPECT_TRUE(mentions(f.check(), "draw 1: indices 4..7 past the index buffer's 6"));

    f = Fixture();
    f.draws[0].indexCount = 2;
    EXPECT_TRUE(mentions(f.check(), "draw 0: 2 indices are not whole triangles"));

    f = Fixture();
    EXPECT_TRUE(mentions(f.check(5), "draw 1: index 5 names LOD vertex 5 of 5")); // vertexOffset 3 + index 2

    f = Fixture();
    f.draws[1].vertexOffset = -1;
    EXPECT_TRUE(mentions(f.check(), "draw 1: index 3 names LOD vertex -1 of 6"));

    f = Fixture();
    EXPECT_TRUE(mentions(f.check(6, 9), "draw 1: visible range 4..10 past the visible list's 9"));

    f = Fixture();
    f.draws[0].instanceCount = 5;
    EXPECT_TRUE(mentions(f.check(), "draw 0: 5 instances in a range of 4"));
}
