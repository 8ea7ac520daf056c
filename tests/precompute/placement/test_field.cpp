// The field (precompute/placement/field.h, terrain.h): the terrain's heights and normals, the flat
// instance lists of a tiling on the terrain, the 3D overlap check and its resolution (verified by
// brute force), determinism, the default 15 x 15 field's numbers and bad parameters.
#include "core/error.h"
#include "core/random.h"
#include "placement/field.h"
#include "placement_fixtures.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace meadow {
namespace {

using test::defaultFill;
using test::irisVolumes;
using test::rockVolumes;

TEST(Terrain, BoundedSmoothAndItsNormalsMatchItsSlopes) {
    const TerrainParams params{1.5f, 30.0f, 3, 42};
    const Terrain terrain(params);
    Random random(1);
    float lowest = 0.0f, highest = 0.0f;
    for (int i = 0; i < 20000; ++i) {
        const float x = random.uniform(-200.0f, 200.0f), z = random.uniform(-200.0f, 200.0f);
        const float y = terrain.height(x, z);
        lowest = std::min(lowest, y);
        highest = std::max(highest, y);
        EXPECT_LE(std::abs(y), params.amplitude);
        if (i % 10 != 0)
            continue;
        // Exact derivatives against central differences in double-evaluated float heights: step
        // 1e-2 m, truncation ~ f''' step^2 / 6 (tiny at a 30 m wavelength) plus float rounding of
        // the heights, ~1e-7 m / 1e-2 m.
        const float step = 1e-2f;
        const glm::vec2 g = terrain.gradient(x, z);
        EXPECT_NEAR(g.x, (terrain.height(x + step, z) - terrain.height(x - step, z)) / (2.0f * step), 2e-4f);
        EXPECT_NEAR(g.y, (terrain.height(x, z + step) - terrain.height(x, z - step)) / (2.0f * step), 2e-4f);
        const glm::vec3 n = terrain.normal(x, z);
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(n - glm::normalize(glm::vec3(-g.x, 1.0f, -g.y))), 0.0f, 1e-6f);
    }
    // Hills, not a plane: the heights use a good part of the range.
    EXPECT_GT(highest - lowest, params.amplitude);
    // Deterministic, seed-dependent, flat at zero amplitude.
    EXPECT_EQ(terrain.height(3.0f, 4.0f), Terrain(params).height(3.0f, 4.0f));
    EXPECT_NE(terrain.height(3.0f, 4.0f), Terrain({1.5f, 30.0f, 3, 43}).height(3.0f, 4.0f));
    EXPECT_EQ(Terrain({0.0f, 30.0f, 3, 42}).height(3.0f, 4.0f), 0.0f);
    EXPECT_THROW(Terrain({std::nanf(""), 30.0f, 3, 0}), Error);
    EXPECT_THROW(Terrain({-1.0f, 30.0f, 3, 0}), Error);
    EXPECT_THROW(Terrain({1.0f, 0.0f, 3, 0}), Error);
    EXPECT_THROW(Terrain({1.0f, 30.0f, 0, 0}), Error);
    EXPECT_THROW(Terrain({1.0f, 30.0f, 13, 0}), Error);
}

struct Placed {
    const SweptVolume* volume;
    InstanceTransform transform;
};

std::vector<Placed> placedOf(const Field& field) {
    std::vector<Placed> all;
    for (const PlacedInstance& i : field.clumps)
        all.push_back({&irisVolumes()[i.index], i.transform()});
    for (const PlacedInstance& i : field.rocks)
        all.push_back({&rockVolumes()[i.index], i.transform()});
    return all;
}

// Every overlapping pair, by brute force over all pairs (no hash grid).
uint64_t bruteForceOverlaps(const Field& field) {
    const std::vector<Placed> all = placedOf(field);
    uint64_t overlaps = 0;
    for (size_t i = 0; i < all.size(); ++i)
        for (size_t j = i + 1; j < all.size(); ++j) {
            const glm::vec3 d = all[i].transform.position - all[j].transform.position;
            const float reach = all[i].volume->footprintRadius() + all[j].volume->footprintRadius();
            if (d.x * d.x + d.z * d.z <= reach * reach * 1.001f)
                overlaps += sweptVolumesOverlap(*all[i].volume, all[i].transform, *all[j].volume, all[j].transform,
                                                field.windDirection);
        }
    return overlaps;
}

FieldParams smallField(uint32_t tiles, bool resolve) {
    FieldParams params;
    params.tilesX = tiles;
    params.tilesY = tiles - 1; // not square, to catch a swapped axis
    params.seed = 3;
    params.resolveOverlaps = resolve;
    return params;
}

TEST(Field, InstancesComeFromTheirTilesAndStandOnTheTerrain) {
    const Terrain terrain({1.0f, 25.0f, 3, 9});
    const Field field = buildField(defaultFill(), irisVolumes(), rockVolumes(), terrain, smallField(6, false));
    size_t clumps = 0, rocks = 0;
    for (uint32_t tile : field.tiling.tiles) {
        clumps += defaultFill().tiles[tile].clumps.size();
        rocks += defaultFill().tiles[tile].rocks.size();
    }
    EXPECT_EQ(field.clumps.size(), clumps);
    EXPECT_EQ(field.rocks.size(), rocks);
    EXPECT_EQ(field.tiling.width, 6u);
    EXPECT_EQ(field.tiling.height, 5u);
    EXPECT_EQ(countEdgeMismatches(field.tiling), 0u);
    const glm::vec2 size = glm::vec2(6.0f, 5.0f) * field.tileSize;
    EXPECT_EQ(field.origin, -0.5f * size); // centred on the world origin
    for (const std::vector<PlacedInstance>* list : {&field.clumps, &field.rocks})
        for (const PlacedInstance& i : *list) {
            EXPECT_EQ(i.position.y, terrain.height(i.position.x, i.position.z)); // the same function, exactly
            EXPECT_GE(i.position.x, field.origin.x);
            EXPECT_LE(i.position.x, field.origin.x + size.x);
            EXPECT_GE(i.position.z, field.origin.y);
            EXPECT_LE(i.position.z, field.origin.y + size.y);
        }
    // The first tile's first clump, in world coordinates.
    const TilePlacement& first = defaultFill().tiles[field.tiling.at(0, 0)].clumps[0];
    EXPECT_EQ(field.clumps[0].position.x, field.origin.x + first.position.x);
    EXPECT_EQ(field.clumps[0].position.z, field.origin.y + first.position.y);
    EXPECT_EQ(field.clumps[0].yaw, first.yaw);
    EXPECT_EQ(field.clumps[0].mirrored, first.mirrored);
}

TEST(Field, HillsMakeOverlapsThatTheCheckFindsAndResolves) {
    // Steep hills (2.5 m over an 8 m wavelength) lift neighbours into one another's leaves.
    const Terrain hills({2.5f, 8.0f, 2, 5});
    const Field raw = buildField(defaultFill(), irisVolumes(), rockVolumes(), hills, smallField(6, false));
    EXPECT_GT(raw.overlaps3d.pairsFound, 0u);
    EXPECT_EQ(raw.overlaps3d.pairsRemaining, raw.overlaps3d.pairsFound);
    EXPECT_EQ(bruteForceOverlaps(raw), raw.overlaps3d.pairsFound); // the hash grid misses no pair

    const Field field = buildField(defaultFill(), irisVolumes(), rockVolumes(), hills, smallField(6, true));
    EXPECT_EQ(field.overlaps3d.pairsFound, raw.overlaps3d.pairsFound);
    EXPECT_EQ(field.overlaps3d.pairsRemaining, 0u);
    EXPECT_EQ(bruteForceOverlaps(field), 0u);
    EXPECT_GT(field.overlaps3d.clumpsRemoved + field.overlaps3d.rocksRemoved, 0u);
    EXPECT_LE(field.overlaps3d.clumpsRemoved + field.overlaps3d.rocksRemoved, raw.overlaps3d.pairsFound);
    EXPECT_EQ(field.clumps.size() + field.overlaps3d.clumpsRemoved, raw.clumps.size());
    EXPECT_EQ(field.rocks.size() + field.overlaps3d.rocksRemoved, raw.rocks.size());
    // What remains is the raw field in order, less the dropped instances.
    auto same = [](const PlacedInstance& a, const PlacedInstance& b) {
        return a.position == b.position && a.yaw == b.yaw && a.index == b.index && a.mirrored == b.mirrored;
    };
    size_t next = 0;
    for (const PlacedInstance& kept : field.clumps) {
        while (next < raw.clumps.size() && !same(raw.clumps[next], kept))
            ++next;
        ASSERT_LT(next, raw.clumps.size()) << "a kept clump is not in the raw field in order";
        ++next;
    }
    std::printf("hills: %llu candidate pairs, %u overlaps found, %u clumps and %u rocks dropped, %u left\n",
                (unsigned long long)field.overlaps3d.candidatePairs, field.overlaps3d.pairsFound,
                field.overlaps3d.clumpsRemoved, field.overlaps3d.rocksRemoved, field.overlaps3d.pairsRemaining);
}

TEST(Field, PlantedOverlapIsFound) {
    const Terrain flat({0.0f, 10.0f, 1, 0});
    Field field = buildField(defaultFill(), irisVolumes(), rockVolumes(), flat, smallField(3, true));
    ASSERT_EQ(field.overlaps3d.pairsFound, 0u);
    // A copy of clump 5 moved 5 cm, and a rock dropped on clump 9's rhizome.
    PlacedInstance twin = field.clumps[5];
    twin.position.x += 0.05f;
    field.clumps.push_back(twin);
    PlacedInstance rock = field.rocks[0];
    rock.position = field.clumps[9].position;
    field.rocks[0] = rock;
    const auto pairs = findFieldOverlaps(field, irisVolumes(), rockVolumes());
    const uint32_t twinIndex = uint32_t(field.clumps.size() - 1), rockIndex = uint32_t(field.clumps.size());
    EXPECT_NE(std::find(pairs.begin(), pairs.end(), std::pair<uint32_t, uint32_t>{5, twinIndex}), pairs.end());
    EXPECT_NE(std::find(pairs.begin(), pairs.end(), std::pair<uint32_t, uint32_t>{9, rockIndex}), pairs.end());
    EXPECT_EQ(pairs.size(), bruteForceOverlaps(field));
}

std::vector<uint8_t> bytesOf(const Field& field) {
    std::vector<uint8_t> bytes;
    auto put = [&](const void* data, size_t size) {
        const uint8_t* p = static_cast<const uint8_t*>(data);
        bytes.insert(bytes.end(), p, p + size);
    };
    for (const std::vector<PlacedInstance>* list : {&field.clumps, &field.rocks})
        for (const PlacedInstance& i : *list) {
            put(&i.position, sizeof i.position);
            put(&i.yaw, sizeof i.yaw);
            put(&i.index, sizeof i.index);
            const uint8_t mirrored = i.mirrored;
            put(&mirrored, 1);
        }
    put(field.tiling.tiles.data(), field.tiling.tiles.size() * sizeof(uint32_t));
    return bytes;
}

TEST(Field, DeterministicForTheSeed) {
    const Terrain terrain({1.0f, 25.0f, 3, 9});
    const std::vector<uint8_t> a =
        bytesOf(buildField(defaultFill(), irisVolumes(), rockVolumes(), terrain, smallField(5, true)));
    const std::vector<uint8_t> b =
        bytesOf(buildField(defaultFill(), irisVolumes(), rockVolumes(), terrain, smallField(5, true)));
    EXPECT_EQ(a, b);
    {
        // The 3D check runs on all cores; one thread gives the same field, also on hills where
        // instances are dropped.
        const Terrain hills({2.5f, 8.0f, 2, 5});
        const std::vector<uint8_t> many =
            bytesOf(buildField(defaultFill(), irisVolumes(), rockVolumes(), hills, smallField(5, true)));
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        EXPECT_EQ(many, bytesOf(buildField(defaultFill(), irisVolumes(), rockVolumes(), hills, smallField(5, true))));
    }
    FieldParams other = smallField(5, true);
    other.seed += 1;
    EXPECT_NE(a, bytesOf(buildField(defaultFill(), irisVolumes(), rockVolumes(), terrain, other)));
    EXPECT_NE(a, bytesOf(buildField(defaultFill(), irisVolumes(), rockVolumes(), Terrain({1.0f, 25.0f, 3, 10}),
                                    smallField(5, true))));
}

TEST(Field, DefaultFieldNumbers) {
    // The paper's field: 15 x 15 tiles from the filled set, 4 clumps, default fill and terrain.
    // Timed from the swept volumes on (tests never assert a time; the figure is printed).
    const auto start = std::chrono::steady_clock::now();
    const WangTileFill fill = fillWangTiles(irisVolumes(), rockVolumes(), test::defaultFillParams());
    const auto filled = std::chrono::steady_clock::now();
    const Field field = buildField(fill, irisVolumes(), rockVolumes(), Terrain(TerrainParams{}), FieldParams{});
    const auto built = std::chrono::steady_clock::now();
    const double fillSeconds = std::chrono::duration<double>(filled - start).count();
    const double fieldSeconds = std::chrono::duration<double>(built - filled).count();
    std::printf("15 x 15 field: %zu clumps, %zu rocks; 3D: %llu candidate pairs, %u overlaps found, %u clumps and "
                "%u rocks dropped, %u left; fill %.3f s, field %.3f s\n",
                field.clumps.size(), field.rocks.size(), (unsigned long long)field.overlaps3d.candidatePairs,
                field.overlaps3d.pairsFound, field.overlaps3d.clumpsRemoved, field.overlaps3d.rocksRemoved,
                field.overlaps3d.pairsRemaining, fillSeconds, fieldSeconds);
    EXPECT_EQ(field.tilesX, 15u);
    EXPECT_EQ(field.tiling.tiles.size(), 225u);
    EXPECT_GT(field.clumps.size(), 5000u); // the paper's field holds ~7,700
    EXPECT_GT(field.rocks.size(), 1000u);  // "thousands of rock instances"
    EXPECT_EQ(field.overlaps3d.pairsRemaining, 0u);
}

TEST(Field, BadParametersGiveClearErrors) {
    const Terrain flat({0.0f, 10.0f, 1, 0});
    FieldParams params;
    params.tilesX = 0;
    EXPECT_THROW(buildField(defaultFill(), irisVolumes(), rockVolumes(), flat, params), Error);
    const std::vector<SweptVolume> oneClump{irisVolumes()[0]};
    try {
        buildField(defaultFill(), oneClump, rockVolumes(), flat, FieldParams{});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("clump"), std::string::npos) << e.what();
    }
    EXPECT_THROW(buildField(defaultFill(), std::vector<SweptVolume>{}, rockVolumes(), flat, FieldParams{}), Error);
    EXPECT_THROW(buildField(defaultFill(), irisVolumes(), std::vector<SweptVolume>{}, flat, FieldParams{}), Error);
}

} // namespace
} // namespace meadow
