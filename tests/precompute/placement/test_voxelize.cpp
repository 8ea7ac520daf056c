// Swept-volume voxelization (precompute/placement/swept_volume.h, triangle_box.h): known shapes
// hit exactly the expected cells, thin slivers never slip through, dilation, solid fill, frame
// selection, determinism and bad input.
#include "core/error.h"
#include "core/random.h"
#include "placement/swept_volume.h"
#include "placement/triangle_box.h"
#include "placement_fixtures.h"
#include "plants/iris.h"
#include "plants/rock.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

namespace meadow {
namespace {

using Cell = std::tuple<int, int, int>;
using test::expectError;
std::set<Cell> cellSet(const SweptVolume& volume) {
    std::set<Cell> out;
    for (const glm::ivec3& c : volume.cells())
        out.insert({c.x, c.y, c.z});
    return out;
}

SweptVolume voxelizeOne(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                        VoxelizeParams params) {
    const std::vector<std::vector<glm::vec3>> frames{positions};
    return voxelizeSweptSurface(indices, frames, params);
}

// An axis-aligned box as 12 triangles, wound outward.
void boxMesh(glm::vec3 lo, glm::vec3 hi, std::vector<glm::vec3>& positions, std::vector<uint32_t>& indices) {
    for (int i = 0; i < 8; ++i)
        positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
    indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
               2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
}

TEST(TriangleBox, SeparatingAxes) {
    const glm::dvec3 centre(0.0), half(0.5);
    // Inside, outside, touching a face (closed: counts).
    EXPECT_TRUE(triangleBoxOverlap(centre, half, {-0.1, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}));
    EXPECT_FALSE(triangleBoxOverlap(centre, half, {2, 0, 0}, {3, 0, 0}, {2, 1, 0}));
    EXPECT_TRUE(triangleBoxOverlap(centre, half, {0.5, -1, -1}, {0.5, 1, -1}, {0.5, 0, 1}));
    EXPECT_FALSE(triangleBoxOverlap(centre, half, {0.5001, -1, -1}, {0.5001, 1, -1}, {0.5001, 0, 1}));
    // Bounding boxes overlap, yet the triangle (in the plane x + y = 1.2) passes beyond the box's
    // edge at x + y = 1; moved to x + y = 0.9 it cuts the box.
    EXPECT_FALSE(triangleBoxOverlap(centre, half, {1.2, 0.0, -0.3}, {0.0, 1.2, -0.3}, {0.6, 0.6, 0.3}));
    EXPECT_TRUE(triangleBoxOverlap(centre, half, {0.9, 0.0, -0.3}, {0.0, 0.9, -0.3}, {0.45, 0.45, 0.3}));
    // A tilted triangle near the corner (0.5, 0.5, 0.5), where x + y + z = 1.5: the plane
    // x + y + z = 1.6 misses the box, x + y + z = 1.4 cuts its corner.
    EXPECT_FALSE(triangleBoxOverlap(centre, half, {1.6, 0, 0}, {0, 1.6, 0}, {0, 0, 1.6}));
    EXPECT_TRUE(triangleBoxOverlap(centre, half, {1.4, 0, 0}, {0, 1.4, 0}, {0, 0, 1.4}));
    // Degenerate: a segment through the box, and a point outside.
    EXPECT_TRUE(triangleBoxOverlap(centre, half, {-2, 0.1, 0.1}, {2, 0.1, 0.1}, {2, 0.1, 0.1}));
    EXPECT_FALSE(triangleBoxOverlap(centre, half, {0.6, 0.6, 0.6}, {0.6, 0.6, 0.6}, {0.6, 0.6, 0.6}));
}

TEST(Voxelize, SingleBigTriangleHitsExactlyItsCells) {
    // h = 1/4 keeps every coordinate exact. The triangle {x >= 0.1, y >= 0.1, x + y <= 2} lies in
    // the plane z = 0.375, the middle of cell layer k = 1: expected are the cells (i, j, 1) whose
    // closed square meets the triangle, i.e. (max(x0, 0.1) + max(y0, 0.1) <= 2) with x1, y1 >= 0.1.
    const float h = 0.25f;
    const SweptVolume volume =
        voxelizeOne({{0.1f, 0.1f, 0.375f}, {1.9f, 0.1f, 0.375f}, {0.1f, 1.9f, 0.375f}}, {0, 1, 2}, {h, 0.0f, false});
    std::set<Cell> expected;
    for (int i = -2; i < 12; ++i)
        for (int j = -2; j < 12; ++j) {
            const double x0 = i * 0.25, y0 = j * 0.25, x1 = x0 + 0.25, y1 = y0 + 0.25;
            if (x1 >= 0.1 && y1 >= 0.1 && std::max(x0, 0.1) + std::max(y0, 0.1) <= 2.0)
                expected.insert({i, j, 1});
        }
    EXPECT_EQ(cellSet(volume), expected);
    EXPECT_EQ(volume.voxelCount(), expected.size());
}

TEST(Voxelize, TriangleOnACellFaceMarksBothSides) {
    // Closed boxes: a surface lying exactly on z = 0.5 (a face between layers 1 and 2) touches the
    // cells on both sides, which the overlap test's conservativeness relies on (instance.h).
    const SweptVolume volume =
        voxelizeOne({{0.1f, 0.1f, 0.5f}, {0.4f, 0.1f, 0.5f}, {0.1f, 0.4f, 0.5f}}, {0, 1, 2}, {0.25f, 0.0f, false});
    // Cell (1, 1) only touches the hypotenuse x + y = 0.5 at its corner (0.25, 0.25): it counts too.
    std::set<Cell> expected;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 1; k < 3; ++k)
                expected.insert({i, j, k});
    EXPECT_EQ(cellSet(volume), expected);
    // Moved off the face by a hair, only one side remains.
    const SweptVolume above = voxelizeOne({{0.1f, 0.1f, 0.5001f}, {0.4f, 0.1f, 0.5001f}, {0.1f, 0.4f, 0.5001f}},
                                          {0, 1, 2}, {0.25f, 0.0f, false});
    EXPECT_EQ(above.minCell().z, 2);
}

TEST(Voxelize, BoxFacesHitExactlyTheShell) {
    // Faces at 0.3 and 1.2 lie inside cells 1 and 4 (h = 1/4): the shell of the 4^3 block 1..4.
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    boxMesh(glm::vec3(0.3f), glm::vec3(1.2f), positions, indices);
    const SweptVolume volume = voxelizeOne(positions, indices, {0.25f, 0.0f, false});
    std::set<Cell> expected;
    for (int i = 1; i <= 4; ++i)
        for (int j = 1; j <= 4; ++j)
            for (int k = 1; k <= 4; ++k)
                if (i == 1 || i == 4 || j == 1 || j == 4 || k == 1 || k == 4)
                    expected.insert({i, j, k});
    EXPECT_EQ(cellSet(volume), expected);
    EXPECT_EQ(volume.voxelCount(), 56u); // 4^3 - 2^3
    EXPECT_EQ(volume.minCell(), glm::ivec3(1));
    EXPECT_EQ(volume.maxCell(), glm::ivec3(4));
    // Solid: the enclosed 2^3 core is filled as well (the box stands above the ground).
    const SweptVolume solid = voxelizeOne(positions, indices, {0.25f, 0.0f, true});
    EXPECT_EQ(solid.voxelCount(), 64u);
}

TEST(Voxelize, ThinSliverMarksEveryCellItPassesThrough) {
    // A blade 1e-5 m wide and 2.9 m long, diagonal to every axis: far thinner than a cell, so
    // sampling its vertices or centres would miss most cells. Every cell the blade's spine passes
    // through must be marked, and every marked cell must touch the blade.
    const float h = 0.1f;
    const glm::vec3 a(0.013f, 0.021f, 0.017f), b(2.31f, 1.77f, 0.93f);
    const glm::vec3 across = glm::normalize(glm::cross(b - a, glm::vec3(0.0f, 0.0f, 1.0f)));
    const SweptVolume volume = voxelizeOne({a, b, b + 1e-5f * across}, {0, 1, 2}, {h, 0.0f, false});
    const int samples = 100000;
    std::set<Cell> crossed;
    std::vector<glm::dvec3> spine;
    for (int s = 0; s <= samples; ++s) {
        const glm::dvec3 p = glm::mix(glm::dvec3(a), glm::dvec3(b), double(s) / samples);
        spine.push_back(p);
        const glm::ivec3 c(glm::floor(p / double(h)));
        crossed.insert({c.x, c.y, c.z});
    }
    const std::set<Cell> marked = cellSet(volume);
    for (const Cell& c : crossed)
        EXPECT_TRUE(marked.count(c)) << "missed cell " << std::get<0>(c) << " " << std::get<1>(c) << " "
                                     << std::get<2>(c);
    // Tightness: each marked box lies within (spine sample spacing 2.9e-5 m + blade width 1e-5 m)
    // of a spine sample.
    for (const Cell& c : marked) {
        const glm::dvec3 lo = glm::dvec3(std::get<0>(c), std::get<1>(c), std::get<2>(c)) * double(h);
        double nearest = 1e9;
        for (const glm::dvec3& p : spine)
            nearest = std::min(nearest, glm::length(p - glm::clamp(p, lo, lo + double(h))));
        EXPECT_LE(nearest, 4e-5) << "cell " << std::get<0>(c) << " " << std::get<1>(c) << " " << std::get<2>(c);
    }
    EXPECT_GE(marked.size(), crossed.size());
}

TEST(Voxelize, SweptVolumeIsTheUnionOfItsFrames) {
    const std::vector<uint32_t> indices{0, 1, 2};
    std::vector<std::vector<glm::vec3>> frames;
    std::set<Cell> unionOfFrames;
    for (int f = 0; f < 5; ++f) {
        const float shift = 0.07f * float(f);
        frames.push_back({{shift, 0.0f, 0.0f}, {0.3f + shift, 0.05f, 0.1f}, {shift, 0.6f, 0.02f}});
        for (const Cell& c : cellSet(voxelizeOne(frames.back(), indices, {0.05f, 0.0f, false})))
            unionOfFrames.insert(c);
    }
    EXPECT_EQ(cellSet(voxelizeSweptSurface(indices, frames, {0.05f, 0.0f, false})), unionOfFrames);
    // The callback form sees the same frames.
    const SweptVolume viaCallback = voxelizeSweptSurface(
        indices, 5, [&](uint32_t frame, std::vector<glm::vec3>& positions) { positions = frames[frame]; },
        {0.05f, 0.0f, false});
    EXPECT_EQ(cellSet(viaCallback), unionOfFrames);
}

TEST(Voxelize, DilationByWholeCells) {
    const float h = 0.1f;
    const std::vector<glm::ivec3> one{{0, 0, 0}};
    const SweptVolume cell = SweptVolume::fromCells(h, one);
    EXPECT_EQ(cell.dilated(0.0f).voxelCount(), 1u);
    EXPECT_EQ(cell.dilated(h).voxelCount(), 27u);                  // k = 1
    EXPECT_EQ(cell.dilated(h * (1.0f + 1e-5f)).voxelCount(), 27u); // within 1e-4 cell of 1: still 1
    EXPECT_EQ(cell.dilated(1.01f * h).voxelCount(), 125u);         // rounded up to k = 2
    EXPECT_EQ(cell.dilated(2.0f * h).minCell(), glm::ivec3(-2));
    EXPECT_EQ(cell.dilated(2.0f * h).maxCell(), glm::ivec3(2));

    // A random cloud: a cell is in the dilation by k iff some original cell is within k cells
    // along every axis (Chebyshev distance), checked by brute force.
    Random random(3);
    std::vector<glm::ivec3> cloud;
    for (int i = 0; i < 30; ++i)
        cloud.push_back({int(random.next() % 10), int(random.next() % 10) - 4, int(random.next() % 10)});
    const SweptVolume volume = SweptVolume::fromCells(h, cloud);
    const int k = 2;
    const SweptVolume grown = volume.dilated(2.0f * h);
    size_t expectedCount = 0;
    for (int x = -4; x < 14; ++x)
        for (int y = -8; y < 10; ++y)
            for (int z = -4; z < 14; ++z) {
                const bool near = std::any_of(cloud.begin(), cloud.end(), [&](const glm::ivec3& c) {
                    return std::abs(c.x - x) <= k && std::abs(c.y - y) <= k && std::abs(c.z - z) <= k;
                });
                EXPECT_EQ(grown.contains({x, y, z}), near) << x << " " << y << " " << z;
                expectedCount += near;
            }
    EXPECT_EQ(grown.voxelCount(), expectedCount);
}

TEST(Voxelize, FootprintRadiusAndHeights) {
    // Cell (2, 0, -1) at h = 0.1: x in [0.2, 0.3], z in [-0.1, 0]: farthest corner (0.3, -0.1).
    const std::vector<glm::ivec3> cells{{2, 0, -1}, {0, 3, 0}};
    const SweptVolume volume = SweptVolume::fromCells(0.1f, cells);
    // Tolerance: float rounding of h * 3 and of the square root (and the one-ulp round-up).
    EXPECT_NEAR(volume.footprintRadius(), std::sqrt(0.1f), 1e-6f);
    EXPECT_GE(double(volume.footprintRadius()), std::sqrt(0.09 + 0.01) - 1e-7);
    EXPECT_NEAR(volume.minY(), 0.0f, 1e-7f);
    EXPECT_NEAR(volume.maxY(), 0.4f, 1e-6f);
}

TEST(Voxelize, ImplicitSphere) {
    const float h = 0.025f, r = 0.3f;
    const glm::vec3 centre(0.0f, 0.5f, 0.0f);
    const SweptVolume sphere = SweptVolume::fromImplicit(
        h, centre - r, centre + r, [&](const glm::vec3& p) { return glm::length(p - centre) <= r; });
    // Cell-centre counting of a 12-cell-radius ball: within 3 % of its volume in cells.
    const double expected = 4.0 / 3.0 * 3.14159265358979 * std::pow(double(r / h), 3.0);
    EXPECT_NEAR(double(sphere.voxelCount()), expected, 0.03 * expected);
    EXPECT_TRUE(sphere.contains(glm::ivec3(glm::floor(centre / h))));
    EXPECT_FALSE(sphere.contains(glm::ivec3(0, 0, 0)));
    // Symmetric under x -> -x about the axis: the lattice is symmetric about cell boundaries at 0.
    for (const glm::ivec3& c : sphere.cells())
        EXPECT_TRUE(sphere.contains({-c.x - 1, c.y, c.z}));
}

// Parity of crossings of the ray from p straight up (Möller-Trumbore): inside a surface that the
// ground closes.
bool insideAboveGround(const RockMesh& rock, const glm::dvec3& p) {
    int crossings = 0;
    const glm::dvec3 up(0.0, 1.0, 0.0);
    for (size_t i = 0; i < rock.indices.size(); i += 3) {
        const glm::dvec3 a(rock.positions[rock.indices[i]]), b(rock.positions[rock.indices[i + 1]]),
            c(rock.positions[rock.indices[i + 2]]);
        const glm::dvec3 e1 = b - a, e2 = c - a, q = glm::cross(up, e2);
        const double det = glm::dot(e1, q);
        if (std::abs(det) < 1e-15)
            continue;
        const glm::dvec3 s = p - a;
        const double u = glm::dot(s, q) / det;
        const glm::dvec3 r = glm::cross(s, e1);
        const double v = glm::dot(up, r) / det, t = glm::dot(e2, r) / det;
        if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0)
            ++crossings;
    }
    return crossings % 2 == 1;
}

TEST(Voxelize, SolidRockHoldsItsInteriorAndNoMore) {
    const RockMesh rock = makeRocks(test::kPlantSeed, 1, rockParamsForPreset("ci"))[0];
    const float h = 0.02f;
    const SweptVolume solid = voxelizeOne(rock.positions, rock.indices, {h, 0.0f, true});
    const SweptVolume shell = voxelizeOne(rock.positions, rock.indices, {h, 0.0f, false});
    EXPECT_GT(solid.voxelCount(), shell.voxelCount());
    for (int x = solid.minCell().x - 1; x <= solid.maxCell().x + 1; ++x)
        for (int y = 0; y <= solid.maxCell().y + 1; ++y)
            for (int z = solid.minCell().z - 1; z <= solid.maxCell().z + 1; ++z) {
                const glm::ivec3 cell(x, y, z);
                if (shell.contains(cell)) {
                    EXPECT_TRUE(solid.contains(cell)); // the surface's own cells stay
                    continue;
                }
                // Off the surface, a cell is solid exactly when its centre is inside the rock
                // (ray parity; centres off the surface's cells are never on the surface).
                const glm::dvec3 centre = (glm::dvec3(cell) + 0.5) * double(h);
                EXPECT_EQ(solid.contains(cell), insideAboveGround(rock, centre)) << x << " " << y << " " << z;
            }
}

TEST(Voxelize, SameCellsForAnyThreadCount) {
    const PlantClump clump = makeIrisClumps(test::kPlantSeed, 1, irisParamsForPreset("ci"))[0];
    const std::vector<std::vector<glm::vec3>> frames = test::leanFrames(clump.mesh, test::kWind, 0.35f);
    SweptVolume one, many;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = voxelizeSweptSurface(clump.mesh.indices, frames, {test::kCellSize, test::kMargin, false});
    }
    many = voxelizeSweptSurface(clump.mesh.indices, frames, {test::kCellSize, test::kMargin, false});
    EXPECT_TRUE(one == many);
    // The lean widens the volume downwind (+x) more than upwind.
    EXPECT_GT(many.maxCell().x, -many.minCell().x);
}

TEST(SelectSweptFrames, LeansTowardTheStrongestLevel) {
    const std::vector<uint32_t> levels{600, 600, 600, 600};
    const std::vector<uint32_t> frames = selectSweptFrames(levels, 64, 0.5f);
    ASSERT_EQ(frames.size(), 64u);
    EXPECT_TRUE(std::is_sorted(frames.begin(), frames.end()));
    EXPECT_EQ(std::adjacent_find(frames.begin(), frames.end()), frames.end()); // distinct
    EXPECT_EQ(std::count_if(frames.begin(), frames.end(), [](uint32_t f) { return f >= 1800; }), 32);
    EXPECT_LT(frames.back(), 2400u);
    // Fewer frames than the budget: all of them.
    const std::vector<uint32_t> few{3, 2};
    EXPECT_EQ(selectSweptFrames(few, 64, 0.5f), (std::vector<uint32_t>{0, 1, 2, 3, 4}));
    const std::vector<uint32_t> strongestOnly = selectSweptFrames(levels, 10, 1.0f);
    EXPECT_TRUE(std::all_of(strongestOnly.begin(), strongestOnly.end(), [](uint32_t f) { return f >= 1800; }));
    EXPECT_THROW(selectSweptFrames(std::vector<uint32_t>{}, 10, 0.5f), Error);
    EXPECT_THROW(selectSweptFrames(std::vector<uint32_t>{5, 0}, 10, 0.5f), Error);
    EXPECT_THROW(selectSweptFrames(levels, 10, std::nanf("")), Error);
}

TEST(Voxelize, BadInputGivesClearErrors) {
    const std::vector<glm::vec3> triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<uint32_t> indices{0, 1, 2};
    expectError([&] { voxelizeOne(triangle, indices, {0.0f, 0.0f, false}); }, "cell size");
    expectError([&] { voxelizeOne(triangle, indices, {-0.02f, 0.0f, false}); }, "cell size");
    expectError([&] { voxelizeOne(triangle, indices, {std::nanf(""), 0.0f, false}); }, "cell size");
    expectError([&] { voxelizeOne(triangle, indices, {0.02f, std::nanf(""), false}); }, "margin");
    expectError([&] { voxelizeOne(triangle, {0, 1}, {0.02f, 0.0f, false}); }, "triangle list");
    expectError([&] { voxelizeOne(triangle, {0, 1, 3}, {0.02f, 0.0f, false}); }, "index 3");
    expectError(
        [&] {
            voxelizeOne({{0, 0, 0}, {1, std::nanf(""), 0}, {0, 1, 0}}, indices, {0.02f, 0.0f, false});
        },
        "not finite");
    expectError([&] { voxelizeSweptSurface(indices, std::span<const std::vector<glm::vec3>>{}, {}); }, "no frames");
    expectError([&] { voxelizeOne(triangle, indices, {1e-5f, 0.0f, false}); }, "too small");
    expectError([&] { SweptVolume::fromCells(0.1f, std::vector<glm::ivec3>{}); }, "no cell");
    expectError([&] { SweptVolume::fromCells(-1.0f, std::vector<glm::ivec3>{{0, 0, 0}}); }, "cell size");
    expectError([&] { SweptVolume::fromCells(0.1f, std::vector<glm::ivec3>{{0, 0, 0}}).dilated(-1.0f); }, "margin");
}

} // namespace
} // namespace meadow
