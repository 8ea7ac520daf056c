// Dart throwing into Wang tiles (precompute/placement/tile_fill.h) with realistic swept volumes:
// no overlap across any tile pair and neighbour offset (independent brute force), none in random
// tilings, the density gain over Poisson discs, determinism and bad parameters.
#include "core/error.h"
#include "placement/field.h"
#include "placement/tile_fill.h"
#include "placement_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace meadow {
namespace {

using test::defaultFill;
using test::defaultFillParams;
using test::expectError;
using test::irisVolumes;
using test::rockVolumes;

struct Item {
    const SweptVolume* volume;
    TilePlacement placement;
};

std::vector<Item> itemsOf(const TileContent& tile) {
    std::vector<Item> items;
    for (const TilePlacement& p : tile.clumps)
        items.push_back({&irisVolumes()[p.index], p});
    for (const TilePlacement& p : tile.rocks)
        items.push_back({&rockVolumes()[p.index], p});
    return items;
}

TEST(TileFill, NoOverlapWithinAnyTileOrAcrossAnyEdgeOrCorner) {
    // Independent of the fill: colours compared here, every ordered tile pair, all 8 offsets,
    // every instance pair (the own tile's pairs once), each by the exact voxel-box test.
    const WangTileFill& fill = defaultFill();
    const float T = fill.tileSize;
    uint64_t testedPairs = 0, violations = 0;
    for (uint32_t t = 0; t < kCompleteWangTileCount; ++t) {
        const WangTile a = wangTileFromIndex(t);
        const std::vector<Item> own = itemsOf(fill.tiles[t]);
        for (size_t i = 0; i < own.size(); ++i)
            for (size_t j = i + 1; j < own.size(); ++j, ++testedPairs)
                violations += sweptVolumesOverlap(*own[i].volume, own[i].placement.transform(), *own[j].volume,
                                                  own[j].placement.transform(), fill.windDirection);
        for (uint32_t u = 0; u < kCompleteWangTileCount; ++u) {
            const WangTile b = wangTileFromIndex(u);
            const std::vector<Item> other = itemsOf(fill.tiles[u]);
            for (int dz = -1; dz <= 1; ++dz)
                for (int dx = -1; dx <= 1; ++dx) {
                    const bool corner = dx != 0 && dz != 0;
                    const bool fits = corner || (dx == 1 && b.w == a.e) || (dx == -1 && b.e == a.w) ||
                                      (dz == 1 && b.n == a.s) || (dz == -1 && b.s == a.n);
                    if ((dx == 0 && dz == 0) || !fits)
                        continue;
                    const glm::vec2 offset = glm::vec2(float(dx), float(dz)) * T;
                    for (const Item& x : own)
                        for (const Item& y : other) {
                            ++testedPairs;
                            violations += sweptVolumesOverlap(*x.volume, x.placement.transform(), *y.volume,
                                                              y.placement.transform(offset), fill.windDirection);
                        }
                }
        }
    }
    EXPECT_EQ(violations, 0u);
    EXPECT_EQ(countTileOverlapViolations(fill, irisVolumes(), rockVolumes()), 0u);
    std::printf("%llu instance pairs tested over 16 tiles, their neighbours and corners: %llu overlaps\n",
                (unsigned long long)testedPairs, (unsigned long long)violations);
}

TEST(TileFill, CountsPerTile) {
    const WangTileFill& fill = defaultFill();
    const std::vector<uint32_t> clumps = fill.clumpsPerTile(), rocks = fill.rocksPerTile();
    ASSERT_EQ(clumps.size(), 16u);
    std::printf("clumps per tile (%.1f m):", double(fill.tileSize));
    for (uint32_t c : clumps)
        std::printf(" %u", c);
    std::printf("\nrocks per tile:");
    for (uint32_t r : rocks)
        std::printf(" %u", r);
    std::printf("\n%.3f clumps per m^2, %llu clump darts, %llu rock darts\n", fill.clumpDensity(),
                (unsigned long long)fill.clumpDarts, (unsigned long long)fill.rockDarts);
    for (size_t t = 0; t < 16; ++t) {
        // A 6 m tile holds dozens of ~1 m wide leaning clumps; rocks fill gaps up to the cap.
        EXPECT_GE(clumps[t], 20u) << "tile " << t;
        EXPECT_GE(rocks[t], 1u) << "tile " << t;
        EXPECT_LE(rocks[t], defaultFillParams().maxRocksPerTile) << "tile " << t;
        for (const TilePlacement& p : fill.tiles[t].clumps) {
            EXPECT_GE(p.position.x, 0.0f);
            EXPECT_LE(p.position.x, fill.tileSize);
            EXPECT_LE(std::abs(p.yaw), defaultFillParams().clumpYawJitter);
            EXPECT_LT(p.index, irisVolumes().size());
        }
    }
}

TEST(TileFill, NoOverlapInRandomTilings) {
    // 20 x 20 tilings, flat ground: every instance pair in reach, by brute force over the flat
    // instance lists (no tiles, no hash grid), a scan-line and a hash tiling.
    const Terrain flat(TerrainParams{0.0f, 10.0f, 1, 0});
    for (const auto& [method, seed] :
         {std::pair{TilingMethod::Scanline, uint64_t(1)}, {TilingMethod::Hash, uint64_t(2)}}) {
        FieldParams params;
        params.tilesX = params.tilesY = 20;
        params.tiling = method;
        params.seed = seed;
        params.resolveOverlaps = false;
        const Field field = buildField(defaultFill(), irisVolumes(), rockVolumes(), flat, params);
        struct Placed {
            const SweptVolume* volume;
            InstanceTransform transform;
        };
        std::vector<Placed> all;
        for (const PlacedInstance& i : field.clumps)
            all.push_back({&irisVolumes()[i.index], i.transform()});
        for (const PlacedInstance& i : field.rocks)
            all.push_back({&rockVolumes()[i.index], i.transform()});
        // Sorted by x, every pair closer in x than the largest reach is tested: all pairs that
        // can overlap, without any grid.
        std::sort(all.begin(), all.end(),
                  [](const Placed& a, const Placed& b) { return a.transform.position.x < b.transform.position.x; });
        float maxReach = 0.0f;
        for (const Placed& p : all)
            maxReach = std::max(maxReach, 2.0f * p.volume->footprintRadius());
        uint64_t violations = 0;
        for (size_t i = 0; i < all.size(); ++i)
            for (size_t j = i + 1; j < all.size(); ++j) {
                const glm::vec3 d = all[i].transform.position - all[j].transform.position;
                if (-d.x > maxReach)
                    break;
                const float reach = all[i].volume->footprintRadius() + all[j].volume->footprintRadius();
                if (d.x * d.x + d.z * d.z <= reach * reach * 1.001f)
                    violations += sweptVolumesOverlap(*all[i].volume, all[i].transform, *all[j].volume,
                                                      all[j].transform, field.windDirection);
            }
        EXPECT_EQ(violations, 0u) << "method " << int(method) << " seed " << seed;
        EXPECT_EQ(field.overlaps3d.pairsFound, 0u);
        EXPECT_GT(all.size(), 400u * 20u);
    }
}

TEST(TileFill, DenserThanPoissonDiscs) {
    const PoissonDiscFill discs = fillWangTilesPoissonDisc(irisVolumes(), defaultFillParams());
    const double ratio = densityVsPoissonDisc(defaultFill(), discs);
    std::printf("footprint radii:");
    for (const SweptVolume& v : irisVolumes())
        std::printf(" %.3f", double(v.footprintRadius()));
    std::printf(" m\nPoisson-disc clumps per tile:");
    for (uint32_t c : discs.clumpsPerTile())
        std::printf(" %u", c);
    std::printf("\ndensityVsPoissonDisc = %.3f (voxels %.3f, discs %.3f clumps per m^2)\n", ratio,
                defaultFill().clumpDensity(), discs.clumpDensity());
    EXPECT_GE(ratio, 1.5); // docs/BENCHMARKS.md, The numbers meadow holds itself to
    // The baseline itself respects its rule: no two discs overlap in any tile or neighbour.
    for (uint32_t t = 0; t < kCompleteWangTileCount; ++t)
        for (uint32_t u = 0; u < kCompleteWangTileCount; ++u)
            for (int dz = -1; dz <= 1; ++dz)
                for (int dx = -1; dx <= 1; ++dx) {
                    const bool self = dx == 0 && dz == 0;
                    if ((self && t != u) ||
                        (!self && !canNeighbour(wangTileFromIndex(t), wangTileFromIndex(u), dx, dz)))
                        continue;
                    for (size_t i = 0; i < discs.tiles[t].size(); ++i)
                        for (size_t j = self ? i + 1 : 0; j < discs.tiles[u].size(); ++j) {
                            const TilePlacement &a = discs.tiles[t][i], &b = discs.tiles[u][j];
                            const glm::vec2 d =
                                b.position + glm::vec2(float(dx), float(dz)) * discs.tileSize - a.position;
                            // Tolerance: float rounding of positions of a few metres.
                            EXPECT_GE(glm::length(d), irisVolumes()[a.index].footprintRadius() +
                                                          irisVolumes()[b.index].footprintRadius() - 1e-5f);
                        }
                }
}

bool sameFill(const WangTileFill& a, const WangTileFill& b) {
    auto same = [](const std::vector<TilePlacement>& x, const std::vector<TilePlacement>& y) {
        if (x.size() != y.size())
            return false;
        for (size_t i = 0; i < x.size(); ++i)
            if (std::memcmp(&x[i].position, &y[i].position, sizeof(glm::vec2)) != 0 || x[i].yaw != y[i].yaw ||
                x[i].mirrored != y[i].mirrored || x[i].index != y[i].index)
                return false;
        return true;
    };
    for (size_t t = 0; t < a.tiles.size(); ++t)
        if (!same(a.tiles[t].clumps, b.tiles[t].clumps) || !same(a.tiles[t].rocks, b.tiles[t].rocks))
            return false;
    return true;
}

TEST(TileFill, DeterministicForTheSeed) {
    TileFillParams params = defaultFillParams();
    params.tileSize = 3.0f; // smaller tiles keep this quick
    const WangTileFill a = fillWangTiles(irisVolumes(), rockVolumes(), params);
    const WangTileFill b = fillWangTiles(irisVolumes(), rockVolumes(), params);
    EXPECT_TRUE(sameFill(a, b));
    params.seed += 1;
    EXPECT_FALSE(sameFill(a, fillWangTiles(irisVolumes(), rockVolumes(), params)));
}

TEST(TileFill, DartBudget) {
    TileFillParams params = defaultFillParams();
    params.maxDarts = 5;
    const WangTileFill fill = fillWangTiles(irisVolumes(), rockVolumes(), params);
    EXPECT_LE(fill.clumpDarts, 16u * 5u);
    EXPECT_LE(fill.rockDarts, 16u * 5u);
    params = defaultFillParams();
    params.maxConsecutiveFailures = 1;
    params.maxRocksPerTile = 0;
    const WangTileFill quick = fillWangTiles(irisVolumes(), rockVolumes(), params);
    EXPECT_EQ(quick.rockDarts, 0u);
    // With no patience the fill stops at its first rejection: far fewer clumps than the default.
    size_t clumps = 0;
    for (uint32_t c : quick.clumpsPerTile())
        clumps += c;
    EXPECT_LT(clumps * 2, size_t(defaultFill().clumpDensity() * 16.0 * 36.0));
}

TEST(TileFill, BadParametersGiveClearErrors) {
    const std::vector<SweptVolume> none;
    auto fillWith = [](auto change) {
        TileFillParams params = defaultFillParams();
        change(params);
        fillWangTiles(irisVolumes(), rockVolumes(), params);
    };
    expectError([&] { fillWangTiles(none, rockVolumes(), defaultFillParams()); }, "clump list is empty");
    expectError([&] { fillWith([](TileFillParams& p) { p.tileSize = 1.0f; }); }, "smaller than a clump");
    expectError([&] { fillWith([](TileFillParams& p) { p.tileSize = std::nanf(""); }); }, "tile size");
    expectError([&] { fillWith([](TileFillParams& p) { p.tileSize = -6.0f; }); }, "tile size");
    expectError([&] { fillWith([](TileFillParams& p) { p.windDirection = glm::vec2(0.0f); }); }, "wind direction");
    expectError([&] { fillWith([](TileFillParams& p) { p.windDirection.x = std::nanf(""); }); }, "wind direction");
    expectError([&] { fillWith([](TileFillParams& p) { p.clumpYawJitter = -0.1f; }); }, "yaw jitter");
    expectError([&] { fillWith([](TileFillParams& p) { p.clumpYawJitter = std::nanf(""); }); }, "yaw jitter");
    expectError([&] { fillWith([](TileFillParams& p) { p.maxDarts = 0; }); }, "dart budget");
    const std::vector<glm::ivec3> one{{0, 0, 0}};
    const std::vector<SweptVolume> coarse{SweptVolume::fromCells(0.05f, one)};
    expectError([&] { fillWangTiles(irisVolumes(), coarse, defaultFillParams()); }, "cell size");
    expectError([&] { fillWangTilesPoissonDisc(std::vector<float>{}, defaultFillParams()); }, "clump list is empty");
    expectError(
        [&] {
            fillWangTilesPoissonDisc(std::vector<float>{0.4f, std::nanf("")}, defaultFillParams());
        },
        "radius");
    expectError([&] { fillWangTilesPoissonDisc(std::vector<float>{4.0f}, defaultFillParams()); },
                "smaller than a clump");
}

} // namespace
} // namespace meadow
