// Placed swept volumes (precompute/placement/instance.h, occupancy_grid.h): the transform's mirror
// and yaw, the exact voxel-box overlap test on known cases, and on random pairs against the
// surfaces themselves (triangle intersection and densely sampled distances) and an all-pairs box
// test: symmetric, never missing a contact, and no more than the cells make.
#include "core/error.h"
#include "core/random.h"
#include "placement/instance.h"
#include "placement/occupancy_grid.h"
#include "placement/swept_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

namespace meadow {
namespace {

const glm::vec2 kWind{0.6f, 0.8f}; // not along an axis, so the mirror is a general reflection

TEST(InstanceTransform, MirrorKeepsTheWindAndYawMatchesTheShader) {
    const glm::dmat2 mirror = horizontalMap(0.0f, true, kWind);
    // The map normalises the float direction in double; tolerances: a few double roundings of
    // products of values <= 1.
    const glm::dvec2 wind = glm::normalize(glm::dvec2(kWind)), across(-wind.y, wind.x);
    EXPECT_NEAR(glm::length(mirror * wind - wind), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(mirror * across + across), 0.0, 1e-12);
    EXPECT_NEAR(glm::determinant(mirror), -1.0, 1e-12);
    EXPECT_NEAR(glm::length((mirror * mirror) * across - across), 0.0, 1e-12); // an involution
    // The engine's instance.vert.glsl: x' = c x + s z, z' = -s x + c z.
    const float yaw = 0.7f;
    const glm::dvec3 p = instanceToWorld({glm::vec3(1.0f, 2.0f, 3.0f), yaw, false}, kWind, glm::vec3(0.3f, 0.4f, 0.5f));
    const double c = std::cos(double(yaw)), s = std::sin(double(yaw));
    EXPECT_NEAR(p.x, 1.0 + c * 0.3f + s * 0.5f, 1e-6);
    EXPECT_NEAR(p.y, 2.4, 1e-6);
    EXPECT_NEAR(p.z, 3.0 - s * 0.3f + c * 0.5f, 1e-6);
    // Mirror first, then yaw.
    const glm::dmat2 difference = horizontalMap(yaw, true, kWind) - horizontalMap(yaw, false, kWind) * mirror;
    EXPECT_NEAR(glm::length(difference[0]) + glm::length(difference[1]), 0.0, 1e-12);
    EXPECT_THROW(horizontalMap(0.0f, true, glm::vec2(0.0f)), Error);
    EXPECT_THROW(horizontalMap(std::nanf(""), false, kWind), Error);
}

SweptVolume singleCell(glm::ivec3 cell, float h = 0.1f) {
    const std::vector<glm::ivec3> cells{cell};
    return SweptVolume::fromCells(h, cells);
}

TEST(SweptVolumesOverlap, KnownBoxes) {
    const SweptVolume cell = singleCell({0, 0, 0}); // [0, 0.1]^3 about its instance's origin
    const glm::vec2 wind(1.0f, 0.0f);
    auto at = [](float x, float y, float z, float yaw = 0.0f, bool mirrored = false) {
        return InstanceTransform{glm::vec3(x, y, z), yaw, mirrored};
    };
    // Side by side: a gap of 1e-4 m, exact touching (does not count), an overlap of 1e-4 m.
    EXPECT_FALSE(sweptVolumesOverlap(cell, at(0, 0, 0), cell, at(0.1001f, 0, 0), wind));
    EXPECT_FALSE(sweptVolumesOverlap(cell, at(0, 0, 0), cell, at(0.1f, 0, 0), wind));
    EXPECT_TRUE(sweptVolumesOverlap(cell, at(0, 0, 0), cell, at(0.0999f, 0, 0), wind));
    // Stacked: the same in height, at a height that is not a whole cell.
    EXPECT_FALSE(sweptVolumesOverlap(cell, at(0, 0.37f, 0), cell, at(0.05f, 0.4701f, 0.02f), wind));
    EXPECT_TRUE(sweptVolumesOverlap(cell, at(0, 0.37f, 0), cell, at(0.05f, 0.4699f, 0.02f), wind));
    // Turned 45 degrees about its origin, the cell's far corner is a tip at (0.1 sqrt 2, 0): a
    // box whose face lies 1e-4 m beyond the tip misses it, 1e-4 m before it is pierced.
    const float tip = 0.1f * std::sqrt(2.0f), quarter = glm::quarter_pi<float>();
    EXPECT_FALSE(sweptVolumesOverlap(cell, at(0, 0, 0, quarter), cell, at(tip + 1e-4f, 0, -0.05f), wind));
    EXPECT_TRUE(sweptVolumesOverlap(cell, at(0, 0, 0, quarter), cell, at(tip - 1e-4f, 0, -0.05f), wind));
    // Mirrored about the plane of the wind (x axis): a cell at z in [0.1, 0.2] goes to [-0.2, -0.1].
    const SweptVolume north = singleCell({0, 0, 1});
    EXPECT_TRUE(sweptVolumesOverlap(north, at(0, 0, 0, 0, true), cell, at(0.0f, 0, -0.15f), wind));
    EXPECT_FALSE(sweptVolumesOverlap(north, at(0, 0, 0, 0, true), cell, at(0.0f, 0, 0.15f), wind));
    EXPECT_TRUE(sweptVolumesOverlap(north, at(0, 0, 0, 0, false), cell, at(0.0f, 0, 0.15f), wind));
    // Far apart, and identical placements.
    EXPECT_FALSE(sweptVolumesOverlap(cell, at(0, 0, 0), cell, at(5, 0, 0), wind));
    EXPECT_TRUE(sweptVolumesOverlap(cell, at(1, 2, 3, 0.3f), cell, at(1, 2, 3, 0.3f), wind));
    EXPECT_THROW(sweptVolumesOverlap(cell, at(0, 0, 0), singleCell({0, 0, 0}, 0.2f), at(0, 0, 0), wind), Error);
}

// ---- Random pairs against the surfaces ------------------------------------------------------------

struct Shape {
    std::vector<uint32_t> indices;
    std::vector<std::vector<glm::vec3>> frames;
};

// Three random blades (triangles up to ~0.35 m) above the ground near the origin, in two frames
// (the second leaning up to 8 cm downwind).
Shape randomShape(Random& random) {
    Shape shape;
    shape.frames.resize(2);
    for (uint32_t t = 0; t < 3; ++t) {
        const glm::vec3 base(random.uniform(-0.2f, 0.2f), random.uniform(0.0f, 0.3f), random.uniform(-0.2f, 0.2f));
        for (int v = 0; v < 3; ++v) {
            const glm::vec3 p = v == 0 ? base
                                       : base + glm::vec3(random.uniform(-0.2f, 0.2f), random.uniform(0.0f, 0.3f),
                                                          random.uniform(-0.2f, 0.2f));
            shape.frames[0].push_back(p);
            shape.frames[1].push_back(p + glm::vec3(random.uniform(0.0f, 0.08f) * p.y / 0.6f, 0.0f, 0.0f));
            shape.indices.push_back(t * 3 + uint32_t(v));
        }
    }
    return shape;
}

using Triangle = std::array<glm::dvec3, 3>;

std::vector<Triangle> worldTriangles(const Shape& shape, const InstanceTransform& transform, glm::vec2 wind) {
    std::vector<Triangle> out;
    for (const std::vector<glm::vec3>& frame : shape.frames)
        for (size_t i = 0; i < shape.indices.size(); i += 3)
            out.push_back({instanceToWorld(transform, wind, frame[shape.indices[i]]),
                           instanceToWorld(transform, wind, frame[shape.indices[i + 1]]),
                           instanceToWorld(transform, wind, frame[shape.indices[i + 2]])});
    return out;
}

bool segmentHitsTriangle(const glm::dvec3& p, const glm::dvec3& q, const Triangle& t) {
    const glm::dvec3 d = q - p, e1 = t[1] - t[0], e2 = t[2] - t[0], h = glm::cross(d, e2);
    const double det = glm::dot(e1, h);
    if (std::abs(det) < 1e-14)
        return false; // parallel: coplanar contact has measure zero for random shapes
    const glm::dvec3 s = p - t[0];
    const double u = glm::dot(s, h) / det;
    const glm::dvec3 r = glm::cross(s, e1);
    const double v = glm::dot(d, r) / det, w = glm::dot(e2, r) / det;
    return u >= 0.0 && v >= 0.0 && u + v <= 1.0 && w >= 0.0 && w <= 1.0;
}

// Two triangles in general position meet iff an edge of one crosses the other.
bool trianglesIntersect(const Triangle& a, const Triangle& b) {
    for (int i = 0; i < 3; ++i)
        if (segmentHitsTriangle(a[i], a[(i + 1) % 3], b) || segmentHitsTriangle(b[i], b[(i + 1) % 3], a))
            return true;
    return false;
}

// The closest point of a triangle (Ericson, Real-Time Collision Detection, 5.1.5).
glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const Triangle& t) {
    const glm::dvec3 &a = t[0], &b = t[1], &c = t[2];
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0)
        return a;
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return a + ab * (d1 / (d1 - d3));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

// An upper bound on the surfaces' distance, at most `spacing` above the true one: A's surface
// sampled on a barycentric grid against B's exact triangles.
double sampledDistance(const std::vector<Triangle>& a, const std::vector<Triangle>& b, double& spacing) {
    const int n = 24;
    double best = 1e9;
    spacing = 0.0;
    for (const Triangle& t : a) {
        spacing = std::max(
            {spacing, glm::length(t[1] - t[0]) / n, glm::length(t[2] - t[1]) / n, glm::length(t[0] - t[2]) / n});
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                const glm::dvec3 p = t[0] + (t[1] - t[0]) * (double(i) / n) + (t[2] - t[0]) * (double(j) / n);
                for (const Triangle& u : b)
                    best = std::min(best, glm::length(p - closestPointOnTriangle(p, u)));
            }
    }
    return best;
}

// The voxel-box overlap by brute force: every box of a against every box of b, each turned into
// the world, separating axes of the two squares in x-z (plain strict comparisons) and open
// intervals in y. No column index, no candidate lookup, no midpoint frame.
bool bruteForceBoxes(const SweptVolume& a, const InstanceTransform& ta, const SweptVolume& b,
                     const InstanceTransform& tb, glm::vec2 wind) {
    const double h = a.cellSize();
    const glm::dmat2 ma = horizontalMap(ta.yaw, ta.mirrored, wind), mb = horizontalMap(tb.yaw, tb.mirrored, wind);
    const glm::dvec2 axes[4] = {ma[0], ma[1], mb[0], mb[1]};
    for (const glm::ivec3& ca : a.cells())
        for (const glm::ivec3& cb : b.cells()) {
            const double loA = ta.position.y + ca.y * h, loB = tb.position.y + cb.y * h;
            if (!(loA < loB + h && loB < loA + h))
                continue;
            const glm::dvec2 centreA =
                glm::dvec2(ta.position.x, ta.position.z) + ma * (glm::dvec2(ca.x, ca.z) + 0.5) * h;
            const glm::dvec2 centreB =
                glm::dvec2(tb.position.x, tb.position.z) + mb * (glm::dvec2(cb.x, cb.z) + 0.5) * h;
            bool separated = false;
            for (const glm::dvec2& n : axes) {
                const double reach = 0.5 * h *
                                     (std::abs(glm::dot(ma[0], n)) + std::abs(glm::dot(ma[1], n)) +
                                      std::abs(glm::dot(mb[0], n)) + std::abs(glm::dot(mb[1], n)));
                separated = separated || !(std::abs(glm::dot(centreA - centreB, n)) < reach);
            }
            if (!separated)
                return true;
        }
    return false;
}

void checkRandomPairs(float margin, uint64_t seed) {
    const float h = 0.05f;
    const int marginCells = int(std::ceil(margin / h - 1e-4f));
    Random random(seed);
    int contacts = 0, exactOverlaps = 0, gridOverlaps = 0, pairs = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const Shape shapeA = randomShape(random), shapeB = randomShape(random);
        const SweptVolume a = voxelizeSweptSurface(shapeA.indices, shapeA.frames, {h, margin, false});
        const SweptVolume b = voxelizeSweptSurface(shapeB.indices, shapeB.frames, {h, margin, false});
        // B within reach of A, any yaw, either mirror; heights either arbitrary (exact test) or
        // whole cells (also the grid, which needs them).
        const bool onLattice = trial % 2 == 0;
        const float angle = random.uniform(0.0f, glm::two_pi<float>());
        const float distance = random.uniform(0.0f, 1.1f * (a.footprintRadius() + b.footprintRadius()));
        InstanceTransform ta{glm::vec3(random.uniform(-1.0f, 1.0f), 0.0f, random.uniform(-1.0f, 1.0f)),
                             random.uniform(-3.2f, 3.2f), random.uniform() < 0.5f};
        InstanceTransform tb{ta.position + distance * glm::vec3(std::cos(angle), 0.0f, std::sin(angle)),
                             random.uniform(-3.2f, 3.2f), random.uniform() < 0.5f};
        if (onLattice) {
            tb.position.y = h * float(int(random.next() % 5) - 2);
        } else {
            ta.position.y = random.uniform(-0.1f, 0.1f);
            tb.position.y = random.uniform(-0.1f, 0.1f);
        }
        const std::vector<Triangle> worldA = worldTriangles(shapeA, ta, kWind),
                                    worldB = worldTriangles(shapeB, tb, kWind);
        bool contact = false;
        for (const Triangle& u : worldA)
            for (const Triangle& v : worldB)
                contact = contact || trianglesIntersect(u, v);

        const bool exact = sweptVolumesOverlap(a, ta, b, tb, kWind);
        ASSERT_EQ(exact, sweptVolumesOverlap(b, tb, a, ta, kWind)) << "asymmetric, trial " << trial;
        EXPECT_EQ(exact, bruteForceBoxes(a, ta, b, tb, kWind)) << "differs from all-pairs boxes, trial " << trial;
        if (contact) {
            EXPECT_TRUE(exact) << "missed a contact of the surfaces, trial " << trial;
        }
        double spacing = 0.0;
        const double distanceOfSurfaces = sampledDistance(worldA, worldB, spacing);
        // Overlapping boxes lie within sqrt(3) h (k + 1) of their surfaces (a touched cell, then
        // k cells of dilation), so the surfaces are within twice that of each other; the sampled
        // distance exceeds the true one by at most the sample spacing.
        const double reach = 2.0 * std::sqrt(3.0) * h * (marginCells + 1);
        if (exact) {
            EXPECT_LE(distanceOfSurfaces, reach + spacing) << "trial " << trial;
        }

        if (onLattice) {
            OccupancyGrid grid(h, glm::vec2(-3.0f), glm::vec2(3.0f), -30, 40, kWind);
            grid.insert(a, ta);
            const bool coarse = grid.overlaps(b, tb);
            // The grid never misses what the exact test sees; its widening of turned columns adds
            // at most about (sqrt(2) - 1) h per side plus a cell of quantisation.
            if (exact) {
                EXPECT_TRUE(coarse) << "grid missed an overlap, trial " << trial;
            }
            if (coarse) {
                EXPECT_LE(distanceOfSurfaces, reach + 3.0 * h + spacing) << "trial " << trial;
            }
            gridOverlaps += coarse;
        }
        contacts += contact;
        exactOverlaps += exact;
        ++pairs;
    }
    // Not trivial: many contacts, and many pairs in reach that do not overlap.
    EXPECT_GT(contacts, pairs / 10);
    EXPECT_LT(exactOverlaps, pairs * 9 / 10);
    EXPECT_GE(exactOverlaps, contacts);
    std::printf(
        "margin %.3f m: %d pairs, %d surface contacts, %d voxel overlaps, %d grid overlaps (of %d on lattice)\n",
        double(margin), pairs, contacts, exactOverlaps, gridOverlaps, pairs / 2);
}

TEST(SweptVolumesOverlap, ConservativeAndSymmetricOnRandomPairs) {
    checkRandomPairs(0.0f, 11); // no safety margin: the hardest case for conservativeness
}

TEST(SweptVolumesOverlap, ConservativeWithAMargin) {
    checkRandomPairs(0.05f, 12);
}

TEST(OccupancyGrid, BadUse) {
    const SweptVolume cell = singleCell({0, 0, 0});
    EXPECT_THROW(OccupancyGrid(0.0f, glm::vec2(0.0f), glm::vec2(1.0f), 0, 10, kWind), Error);
    EXPECT_THROW(OccupancyGrid(0.1f, glm::vec2(1.0f), glm::vec2(0.0f), 0, 10, kWind), Error);
    EXPECT_THROW(OccupancyGrid(0.1f, glm::vec2(0.0f), glm::vec2(1.0f), 10, 0, kWind), Error);
    OccupancyGrid grid(0.1f, glm::vec2(0.0f), glm::vec2(1.0f), 0, 10, kWind);
    EXPECT_THROW(grid.insert(cell, {glm::vec3(0.5f, 0.05f, 0.5f), 0.0f, false}), Error); // half a cell up
    EXPECT_THROW(grid.insert(cell, {glm::vec3(0.5f, 2.0f, 0.5f), 0.0f, false}), Error);  // above the grid
    EXPECT_THROW(grid.insert(singleCell({0, 0, 0}, 0.2f), InstanceTransform{}), Error);
    grid.insert(cell, {glm::vec3(0.5f, 0.0f, 0.5f), 0.0f, false});
    EXPECT_TRUE(grid.overlaps(cell, {glm::vec3(0.55f, 0.0f, 0.45f), 1.0f, true}));
    EXPECT_FALSE(grid.overlaps(cell, {glm::vec3(0.55f, 0.2f, 0.45f), 1.0f, true}));
    grid.clear();
    EXPECT_FALSE(grid.overlaps(cell, {glm::vec3(0.55f, 0.0f, 0.45f), 1.0f, true}));
}

} // namespace
} // namespace meadow
