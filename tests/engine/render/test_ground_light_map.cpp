// The ground light map's static part (render/ground_light_map.h): each instance's caster puts its
// grid where the instance stands, turned and mirrored as its meshes are, and every texel lists the
// cell of every grid that covers its centre, with the bilinear weights there, in instance order.
#include "render/ground_light_map.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <random>

using namespace meadow;

namespace {

// A clump with a grid of `points` a side over `side` m, light variants in `bins` yaw bins over
// [-0.5, 1.0) radians, its ratios from vertex-light vec4 `first`.
gpu::GpuClump gridClump(uint32_t points, float side, uint32_t bins, uint32_t first) {
    gpu::GpuClump c{};
    c.light = glm::uvec4(0u, bins, 0u, 1u);
    c.yawBins = glm::vec4(-0.5f, float(bins) / 1.5f, 1.5f / float(bins), side);
    c.ground = glm::uvec4(0u, first, points, 0u);
    return c;
}

FieldClump fieldClumpOf(const gpu::GpuClump& c) {
    FieldClump f;
    f.groundResolution = c.ground.z;
    f.groundSize = c.yawBins.w;
    return f;
}

struct Field {
    std::vector<gpu::GpuClump> clumps;
    std::vector<FieldClump> fieldClumps;
    std::vector<gpu::GpuInstance> instances;
    GroundLightMapLayout layout;
    glm::vec2 mirrorNormal;
};

Field scatteredField(uint32_t count, uint32_t seed) {
    Field f;
    f.clumps = {gridClump(5, 1.2f, 3, 100), gridClump(2, 0.7f, 1, 300), gridClump(0, 0.0f, 2, 0)};
    for (const gpu::GpuClump& c : f.clumps)
        f.fieldClumps.push_back(fieldClumpOf(c));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t i = 0; i < count; ++i) {
        gpu::GpuInstance inst{};
        const float scale = 0.6f + 1.2f * unit(rng);
        inst.positionScale =
            glm::vec4(8.0f * unit(rng), 0.3f * unit(rng), 5.0f * unit(rng), i % 3 == 1 ? -scale : scale);
        inst.yaw = -1.0f + 3.0f * unit(rng); // inside and outside the bins' range
        inst.mesh = i % 3;
        inst.boundingRadius = 1.0f;
        f.instances.push_back(inst);
    }
    f.layout = groundLightMapLayout(f.fieldClumps, f.instances);
    const glm::vec2 wind = glm::normalize(glm::vec2(1.0f, 0.25f));
    f.mirrorNormal = glm::vec2(-wind.y, wind.x);
    return f;
}

// Where instance.vert puts a clump-space point (x, z) of an instance, in map texels.
glm::vec2 texelOf(const Field& f, const gpu::GpuInstance& inst, glm::vec2 local) {
    glm::vec3 p(local.x, 0.0f, local.y);
    if (inst.positionScale.w < 0.0f) {
        const glm::vec3 m(f.mirrorNormal.x, 0.0f, f.mirrorNormal.y);
        p -= 2.0f * glm::dot(p, m) * m;
    }
    const float s = std::sin(inst.yaw), c = std::cos(inst.yaw);
    const glm::vec2 world = glm::vec2(inst.positionScale.x, inst.positionScale.z) +
                            glm::vec2(c * p.x + s * p.z, -s * p.x + c * p.z) * std::abs(inst.positionScale.w);
    return (world - glm::vec2(f.layout.rect)) * glm::vec2(f.layout.rect.z, f.layout.rect.w) *
           glm::vec2(f.layout.size.width, f.layout.size.height);
}

} // namespace

TEST(GroundLightMap, CastersPutEveryGridPointWhereTheInstanceLaysIt) {
    const Field f = scatteredField(60, 3);
    const std::vector<GroundCaster> casters = groundCasters(f.clumps, f.instances, f.layout, f.mirrorNormal);
    size_t next = 0;
    for (const gpu::GpuInstance& inst : f.instances) {
        const gpu::GpuClump& clump = f.clumps[inst.mesh];
        const uint32_t points = clump.ground.z;
        if (points < 2)
            continue; // no grid, no caster
        ASSERT_LT(next, casters.size());
        const GroundCaster& c = casters[next++];
        const float side = clump.yawBins.w;
        for (uint32_t row = 0; row < points; ++row)
            for (uint32_t column = 0; column < points; ++column) {
                // Grid point (column, row) at x = -side/2 + side column / (points - 1), z with the row.
                const glm::vec2 local(-0.5f * side + side * float(column) / float(points - 1),
                                      -0.5f * side + side * float(row) / float(points - 1));
                const glm::vec2 at = texelOf(f, inst, local);
                const glm::vec2 g = groundGridPoint(c, at);
                EXPECT_NEAR(g.x, float(column), 1e-3f) << "instance yaw " << inst.yaw;
                EXPECT_NEAR(g.y, float(row), 1e-3f) << "instance yaw " << inst.yaw;
                EXPECT_TRUE(at.x >= c.low.x - 1e-3f && at.y >= c.low.y - 1e-3f && at.x <= c.high.x + 1e-3f &&
                            at.y <= c.high.y + 1e-3f);
            }
        // Its variant's ratios: the yaw bin, the mirrored ones after the unmirrored.
        const uint32_t bins = clump.light.y;
        const int bin = std::clamp(int(std::floor((inst.yaw + 0.5f) / 1.5f * float(bins))), 0, int(bins) - 1);
        const uint32_t variant = uint32_t(bin) + (inst.positionScale.w < 0.0f ? bins : 0u);
        EXPECT_EQ(c.first, clump.ground.y + variant * points * points);
        EXPECT_EQ(c.points, points);
    }
    EXPECT_EQ(next, casters.size());
    // A grid finer than the renderer holds is refused, naming its clump.
    Field fine = f;
    fine.clumps[0].ground.z = gpu::kGroundGridMaxPoints + 1;
    EXPECT_THROW(groundCasters(fine.clumps, fine.instances, fine.layout, fine.mirrorNormal), Error);
}

TEST(GroundLightMap, EveryTexelListsTheCellOfEveryGridCoveringItInInstanceOrder) {
    const Field f = scatteredField(200, 11);
    const std::vector<GroundCaster> casters = groundCasters(f.clumps, f.instances, f.layout, f.mirrorNormal);
    const GroundLightMapLists lists = groundLightMapLists(casters, f.layout.size);
    const uint32_t width = f.layout.size.width, height = f.layout.size.height;
    ASSERT_EQ(lists.texelStart.size(), size_t(width) * height + 1);
    ASSERT_EQ(lists.texelStart.back(), lists.entries.size());
    EXPECT_GT(casters.size(), 100u);
    const float unit = float((1u << gpu::kGroundWeightBits) - 1u);
    size_t covered = 0;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            // Brute force over every caster, in order, against the texel's list.
            const size_t t = size_t(y) * width + x;
            uint32_t e = lists.texelStart[t];
            for (const GroundCaster& c : casters) {
                const glm::vec2 g = groundGridPoint(c, glm::vec2(float(x) + 0.5f, float(y) + 0.5f));
                const float last = float(c.points - 1);
                if (g.x < 0.0f || g.y < 0.0f || g.x > last || g.y > last)
                    continue;
                ++covered;
                ASSERT_LT(e, lists.texelStart[t + 1]) << "texel " << x << ", " << y << " misses a grid";
                const glm::uvec2 entry = lists.entries[e++];
                const glm::vec2 cell = glm::min(glm::floor(g), glm::vec2(last - 1.0f));
                EXPECT_EQ(entry.x, c.first + uint32_t(cell.y) * c.points + uint32_t(cell.x));
                EXPECT_EQ(entry.y >> (2 * gpu::kGroundWeightBits), c.points - 1);
                const uint32_t mask = (1u << gpu::kGroundWeightBits) - 1u;
                EXPECT_NEAR(float(entry.y & mask) / unit, g.x - cell.x, 0.501f / unit);
                EXPECT_NEAR(float(entry.y >> gpu::kGroundWeightBits & mask) / unit, g.y - cell.y, 0.501f / unit);
            }
            EXPECT_EQ(e, lists.texelStart[t + 1]) << "texel " << x << ", " << y << " lists a grid that misses it";
        }
    EXPECT_GT(covered, 10000u);
    EXPECT_EQ(covered, lists.entries.size());
}

// The gather's cost is its entries: the texel is 8 cm while the grids list fewer than the budget,
// and coarser, as the grids' area says, where they would list more, so that they list about the
// budget.
TEST(GroundLightMap, TheTexelGrowsToKeepTheListsNearTheirEntryBudget) {
    const Field f = scatteredField(200, 11);
    auto entries = [&](const GroundLightMapLayout& layout) {
        return groundLightMapLists(groundCasters(f.clumps, f.instances, layout, f.mirrorNormal), layout.size)
            .entries.size();
    };
    // The default budget: 8 cm texels (the size is the extent over 8 cm, rounded down).
    ASSERT_GT(f.layout.rect.z, 0.0f);
    EXPECT_EQ(f.layout.size.width, uint32_t(1.0f / f.layout.rect.z / kGroundMapFinestTexel));
    EXPECT_EQ(f.layout.size.height, uint32_t(1.0f / f.layout.rect.w / kGroundMapFinestTexel));
    const size_t fine = entries(f.layout);
    EXPECT_LT(fine, kGroundMapEntryBudget);
    // A budget of a quarter of that: texels about twice as wide, and about the budget's entries.
    const uint64_t budget = fine / 4;
    const GroundLightMapLayout coarse = groundLightMapLayout(f.fieldClumps, f.instances, budget);
    EXPECT_EQ(coarse.rect, f.layout.rect);
    EXPECT_NEAR(double(coarse.size.width) / double(f.layout.size.width), 0.5, 0.05);
    EXPECT_NEAR(double(coarse.size.height) / double(f.layout.size.height), 0.5, 0.05);
    const double listed = double(entries(coarse)) / double(budget);
    EXPECT_GT(listed, 0.8);
    EXPECT_LT(listed, 1.25);
    // A budget above the fine lists changes nothing.
    const GroundLightMapLayout same = groundLightMapLayout(f.fieldClumps, f.instances, 4 * fine);
    EXPECT_EQ(same.size.width, f.layout.size.width);
    EXPECT_EQ(same.size.height, f.layout.size.height);
}

TEST(GroundLightMap, ReferenceMultipliesTheGridsCoveringATexel) {
    // Two unturned instances of a 2-point grid whose ratios are 0.5 and 0.25 everywhere, over each
    // other: 0.125 where both lie, 1 far from them.
    Field f;
    f.clumps = {gridClump(2, 1.0f, 1, 0), gridClump(2, 1.0f, 1, 8)};
    f.fieldClumps = {fieldClumpOf(f.clumps[0]), fieldClumpOf(f.clumps[1])};
    for (uint32_t i = 0; i < 2; ++i) {
        gpu::GpuInstance inst{};
        inst.positionScale = glm::vec4(float(i) * 0.5f, 0.0f, 0.0f, 1.0f);
        inst.yaw = 0.0f;
        inst.mesh = i;
        f.instances.push_back(inst);
    }
    f.layout = groundLightMapLayout(f.fieldClumps, f.instances);
    f.mirrorNormal = glm::vec2(0.0f, 1.0f);
    const std::vector<GroundCaster> casters = groundCasters(f.clumps, f.instances, f.layout, f.mirrorNormal);
    std::vector<glm::uvec4> light(16);
    for (uint32_t i = 0; i < 16; ++i) {
        const float ratio = i < 8 ? 0.5f : 0.25f;
        light[i] =
            glm::uvec4(glm::floatBitsToUint(ratio), glm::floatBitsToUint(ratio), glm::floatBitsToUint(ratio), 0u);
    }
    const std::vector<glm::vec3> map = groundLightMapReference(casters, f.layout.size, light);
    auto at = [&](glm::vec2 world) {
        const glm::vec2 t = (world - glm::vec2(f.layout.rect)) * glm::vec2(f.layout.rect.z, f.layout.rect.w) *
                            glm::vec2(f.layout.size.width, f.layout.size.height);
        return map[size_t(t.y) * f.layout.size.width + size_t(t.x)].x;
    };
    EXPECT_FLOAT_EQ(at({0.25f, 0.1f}), 0.125f);
    EXPECT_FLOAT_EQ(at({-0.3f, 0.1f}), 0.5f);
    EXPECT_FLOAT_EQ(at({0.9f, -0.2f}), 0.25f);
    EXPECT_FLOAT_EQ(at({0.25f, 0.7f}), 1.0f);
    // Too few vertex-light values for a caster: an error, not a read past the end.
    EXPECT_THROW(groundLightMapReference(casters, f.layout.size, std::span<const glm::uvec4>(light).first(10)), Error);
}
