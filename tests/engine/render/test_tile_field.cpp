// meadow bench --clumps: the field tiled to a count keeps the field where it lies, then grows whole
// copies around it, nearest first, so that every count shows the scene camera's view and more.
#include "core/error.h"
#include "render/field_bench.h"

#include <cmath>
#include <gtest/gtest.h>
#include <set>

using namespace meadow;

namespace {

// A 3 x 2 grid of instances over [0, 10] x [0, 4] m.
std::vector<gpu::GpuInstance> smallField() {
    std::vector<gpu::GpuInstance> field;
    for (int z = 0; z < 2; ++z)
        for (int x = 0; x < 3; ++x) {
            gpu::GpuInstance inst{};
            inst.positionScale = glm::vec4(5.0f * float(x), 0.5f, 4.0f * float(z), 1.0f);
            inst.mesh = uint32_t(x + z);
            field.push_back(inst);
        }
    return field;
}

} // namespace

TEST(TileField, FewerThanTheFieldCutsItInPlace) {
    const auto field = smallField();
    const auto cut = tileField(field, 4);
    ASSERT_EQ(cut.size(), 4u);
    for (size_t i = 0; i < cut.size(); ++i) {
        EXPECT_EQ(cut[i].positionScale, field[i].positionScale);
        EXPECT_EQ(cut[i].mesh, field[i].mesh);
    }
}

TEST(TileField, TheFieldStaysWhereItIsAndCopiesRingItNearestFirst) {
    const auto field = smallField();
    const glm::vec2 step(11.0f, 5.0f); // extent + 1 m
    const auto tiled = tileField(field, uint32_t(field.size() * 9 + 2));
    ASSERT_EQ(tiled.size(), field.size() * 9 + 2);
    std::set<std::pair<int, int>> cells;
    float lastRing = 0.0f;
    for (size_t c = 0; c * field.size() < tiled.size(); ++c) {
        const glm::vec4 offset = tiled[c * field.size()].positionScale - field[0].positionScale;
        const glm::ivec2 cell(int(std::lround(offset.x / step.x)), int(std::lround(offset.z / step.y)));
        EXPECT_FLOAT_EQ(offset.x, float(cell.x) * step.x);
        EXPECT_FLOAT_EQ(offset.z, float(cell.y) * step.y);
        EXPECT_EQ(offset.y, 0.0f);
        EXPECT_TRUE(cells.insert({cell.x, cell.y}).second) << "two copies in one cell";
        const float ring = float(std::max(std::abs(cell.x), std::abs(cell.y)));
        EXPECT_GE(ring, lastRing) << "copy " << c << " is nearer than the one before";
        lastRing = ring;
        if (c == 0) {
            EXPECT_EQ(cell, glm::ivec2(0, 0)) << "the field itself comes first, in place";
        }
        // Every copy is the whole field shifted (the last one cut).
        for (size_t i = 0; i < field.size() && c * field.size() + i < tiled.size(); ++i) {
            EXPECT_EQ(tiled[c * field.size() + i].mesh, field[i].mesh);
            EXPECT_EQ(tiled[c * field.size() + i].positionScale, field[i].positionScale + offset);
        }
    }
    EXPECT_EQ(cells.size(), 10u);
    EXPECT_EQ(lastRing, 2.0f); // 9 cells fill the first ring; the tenth opens the second
}

TEST(TileField, AnEmptyFieldIsAnError) {
    EXPECT_THROW(tileField({}, 10), Error);
}
