// Wang tiles (precompute/placement/wang_tiles.h): the complete set and Cohen et al.'s 8, the
// stochastic scan-line tiling, and the direct hash tiling for unbounded fields.
#include "core/error.h"
#include "core/random.h"
#include "placement/wang_tiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

namespace meadow {
namespace {

TEST(WangTiles, CompleteSetAndIndices) {
    std::set<std::array<int, 4>> colourings;
    for (uint32_t i = 0; i < kCompleteWangTileCount; ++i) {
        const WangTile t = wangTileFromIndex(i);
        EXPECT_EQ(wangTileIndex(t), i);
        EXPECT_LE(std::max({t.n, t.e, t.s, t.w}), 1);
        colourings.insert({t.n, t.e, t.s, t.w});
    }
    EXPECT_EQ(colourings.size(), 16u); // every combination of N, E, S, W
}

TEST(WangTiles, CohensEightHaveTwoTilesPerNorthWestPair) {
    const std::array<uint32_t, kCohenWangTileCount> set = cohenWangTiles();
    EXPECT_EQ(std::set<uint32_t>(set.begin(), set.end()).size(), 8u);
    std::map<std::pair<int, int>, std::vector<WangTile>> byNorthWest;
    std::array<std::array<int, 2>, 4> colourCounts{}; // per edge (n, e, s, w), per colour
    for (uint32_t index : set) {
        const WangTile t = wangTileFromIndex(index);
        byNorthWest[{t.n, t.w}].push_back(t);
        ++colourCounts[0][t.n];
        ++colourCounts[1][t.e];
        ++colourCounts[2][t.s];
        ++colourCounts[3][t.w];
    }
    ASSERT_EQ(byNorthWest.size(), 4u);
    for (const auto& [northWest, tiles] : byNorthWest) {
        ASSERT_EQ(tiles.size(), 2u);
        // The two choices differ in both outgoing colours, so each choice steers both neighbours.
        EXPECT_NE(tiles[0].s, tiles[1].s);
        EXPECT_NE(tiles[0].e, tiles[1].e);
    }
    for (const auto& edge : colourCounts)
        EXPECT_EQ(edge, (std::array<int, 2>{4, 4}));
}

TEST(WangTiles, NeighbourRules) {
    for (uint32_t t = 0; t < kCompleteWangTileCount; ++t)
        for (uint32_t u = 0; u < kCompleteWangTileCount; ++u) {
            const WangTile a = wangTileFromIndex(t), b = wangTileFromIndex(u);
            EXPECT_EQ(canNeighbour(a, b, 1, 0), a.e == b.w);
            EXPECT_EQ(canNeighbour(a, b, 0, 1), a.s == b.n); // +z is south
            // Symmetric: u beside t iff t beside u the other way.
            for (int dx = -1; dx <= 1; ++dx)
                for (int dz = -1; dz <= 1; ++dz) {
                    if (dx != 0 || dz != 0) {
                        EXPECT_EQ(canNeighbour(a, b, dx, dz), canNeighbour(b, a, -dx, -dz));
                    }
                }
            EXPECT_TRUE(canNeighbour(a, b, 1, 1));
        }
}

TEST(WangTiles, ScanlineTilingsMatchEverywhere) {
    const std::array<uint32_t, kCohenWangTileCount> set = cohenWangTiles();
    for (uint64_t seed = 0; seed < 20; ++seed)
        for (auto [width, height] : {std::pair{1u, 1u}, {1u, 20u}, {20u, 1u}, {15u, 15u}, {40u, 33u}}) {
            const WangTiling tiling = scanlineWangTiling(width, height, seed);
            ASSERT_EQ(tiling.tiles.size(), size_t(width) * height);
            EXPECT_EQ(countEdgeMismatches(tiling), 0u) << "seed " << seed;
            for (uint32_t tile : tiling.tiles)
                EXPECT_NE(std::find(set.begin(), set.end(), tile), set.end()) << "a tile outside Cohen's 8";
        }
    // Deterministic; another seed gives another tiling.
    EXPECT_EQ(scanlineWangTiling(15, 15, 5).tiles, scanlineWangTiling(15, 15, 5).tiles);
    EXPECT_NE(scanlineWangTiling(15, 15, 5).tiles, scanlineWangTiling(15, 15, 6).tiles);
    // Every tile of the 8 is used about equally: 1600 tiles, each within 8 .. 17 % (the binomial's
    // standard deviation is 0.8 %, so this bound fails only for a biased draw).
    const WangTiling big = scanlineWangTiling(40, 40, 9);
    std::map<uint32_t, int> counts;
    for (uint32_t tile : big.tiles)
        ++counts[tile];
    EXPECT_EQ(counts.size(), 8u);
    for (const auto& [tile, count] : counts) {
        EXPECT_GT(count, 128) << "tile " << tile;
        EXPECT_LT(count, 272) << "tile " << tile;
    }
    EXPECT_THROW(scanlineWangTiling(0, 5, 1), Error);
}

TEST(WangTiles, HashTilingMatchesAndIsOrderFree) {
    const uint64_t seed = 1234;
    const WangTiling window = hashWangTiling(-100, -57, 200, 200, seed);
    EXPECT_EQ(countEdgeMismatches(window), 0u);
    std::set<uint32_t> used(window.tiles.begin(), window.tiles.end());
    EXPECT_EQ(used.size(), 16u); // the complete set is needed
    // Deterministic, and the same tile whatever order the plane is queried in or whichever window
    // holds it.
    EXPECT_EQ(window.tiles, hashWangTiling(-100, -57, 200, 200, seed).tiles);
    const WangTiling shifted = hashWangTiling(-37, 0, 50, 60, seed);
    for (uint32_t y = 0; y < shifted.height; ++y)
        for (uint32_t x = 0; x < shifted.width; ++x)
            EXPECT_EQ(shifted.at(x, y), window.at(x + 63, y + 57));
    Random random(5);
    for (int i = 0; i < 5000; ++i) {
        const uint32_t x = uint32_t(random.next() % 200), y = uint32_t(random.next() % 200);
        EXPECT_EQ(hashWangTileAt(int64_t(x) - 100, int64_t(y) - 57, seed), window.at(x, y));
    }
    // Unbounded: far from the origin the edges still match.
    EXPECT_EQ(countEdgeMismatches(hashWangTiling(1000000000000ll, -999999999999ll, 30, 30, seed)), 0u);
    EXPECT_NE(hashWangTiling(0, 0, 20, 20, seed).tiles, hashWangTiling(0, 0, 20, 20, seed + 1).tiles);
    EXPECT_THROW(hashWangTiling(0, 0, 5, 0, seed), Error);
}

TEST(WangTiles, MismatchCounterSeesBrokenEdges) {
    WangTiling tiling = scanlineWangTiling(4, 4, 3);
    WangTile t = wangTileFromIndex(tiling.at(1, 1));
    t.e ^= 1; // breaks the edge with (2, 1)
    tiling.tiles[1 * 4 + 1] = wangTileIndex(t);
    EXPECT_EQ(countEdgeMismatches(tiling), 1u);
}

} // namespace
} // namespace meadow
