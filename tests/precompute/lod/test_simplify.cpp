// The half-edge collapse simplifier (precompute/lod/simplify.cpp) on shapes with known answers.
#include "lod_fixtures.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

using namespace meadow;
using namespace meadow::test;

namespace {

double signedVolume(const std::vector<glm::vec3>& p, const std::vector<uint32_t>& indices) {
    double volume = 0.0;
    for (size_t i = 0; i < indices.size(); i += 3)
        volume += glm::dot(glm::dvec3(p[indices[i]]),
                           glm::cross(glm::dvec3(p[indices[i + 1]]), glm::dvec3(p[indices[i + 2]])));
    return volume / 6.0;
}

template <typename F> void expectError(F&& f, const std::string& needle) {
    try {
        f();
        ADD_FAILURE() << "no error; expected one containing: " << needle;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "message: " << e.what();
    }
}

// Column of a grid vertex (makeGrid with cellsX = 20 over [0, 1]).
uint32_t column(const TestMesh& grid, uint32_t v) {
    return uint32_t(std::lround(grid.positions[v].x * 20.0f));
}

// True while no triangle straddles column 10 or column 11: the step of an attribute that is 0 up
// to column 10 and 1 from column 11 is still represented.
bool stepIntact(const TestMesh& grid, const SimplifiedMesh& s) {
    const std::vector<uint32_t> tri = originalIndices(s.keptVertices, s.indices);
    for (size_t i = 0; i < tri.size(); i += 3) {
        const uint32_t a = column(grid, tri[i]), b = column(grid, tri[i + 1]), c = column(grid, tri[i + 2]);
        const uint32_t lo = std::min({a, b, c}), hi = std::max({a, b, c});
        if ((lo < 10 && hi > 10) || (lo < 11 && hi > 11))
            return false;
    }
    return true;
}

} // namespace

TEST(Simplify, FlatGridBecomesTwoTrianglesAtTinyError) {
    const TestMesh grid = makeGrid(16, 16);
    const SimplifiedMesh s = simplifyMesh(grid.input(), 2);
    ASSERT_EQ(s.triangleCount(), 2u);
    // A plane with linear UVs and constant normals: every collapse but the corners' is free, and
    // the corners are never needed; what remains is rounding of float positions.
    EXPECT_LT(s.error, 1e-5f);
    EXPECT_EQ(s.keptVertices, (std::vector<uint32_t>{0, 16, 272, 288}));
    EXPECT_EQ(s.stage, SimplifyStage::Constrained);
}

TEST(Simplify, ClosedShapeKeepsItsVolumeAndStaysClosed) {
    const TestMesh sphere = makeIcosphere(4); // 5,120 triangles, 2,562 vertices
    const double before = signedVolume(sphere.positions, sphere.indices);
    ASSERT_NEAR(before, 4.18879, 0.05); // 4/3 pi, less the facets' sagitta
    const SimplifiedMesh s = simplifyMesh(sphere.input(), 512);
    // Each collapse of a closed manifold removes exactly two triangles.
    EXPECT_GE(s.triangleCount(), 510u);
    EXPECT_LE(s.triangleCount(), 512u);
    const std::vector<uint32_t> tri = originalIndices(s.keptVertices, s.indices);
    // Vertices stay on the sphere, so the polyhedron is inscribed: a 258-vertex inscribed
    // polyhedron holds ~97 % of the ball; 5 % is the tolerance for an uneven distribution.
    EXPECT_NEAR(signedVolume(sphere.positions, tri) / before, 1.0, 0.05);
    EXPECT_TRUE(boundaryEdges(tri).empty()) << "a hole opened";
    std::map<std::pair<uint32_t, uint32_t>, int> uses;
    for (size_t i = 0; i < tri.size(); i += 3)
        for (int k = 0; k < 3; ++k)
            ++uses[std::minmax(tri[i + k], tri[i + (k + 1) % 3])];
    for (const auto& [edge, n] : uses)
        EXPECT_EQ(n, 2) << "edge " << edge.first << "-" << edge.second << " is not manifold";

    // Asked for less than a closed surface can have, it stops at a valid closed polyhedron (a
    // tetrahedron at best) instead of pinching or doubling triangles: the link condition.
    const TestMesh small = makeIcosphere(1);
    const SimplifiedMesh tiny = simplifyMesh(small.input(), 2);
    const std::vector<uint32_t> tinyTri = originalIndices(tiny.keptVertices, tiny.indices);
    EXPECT_GE(tiny.triangleCount(), 4u);
    std::map<std::pair<uint32_t, uint32_t>, int> tinyUses;
    for (size_t i = 0; i < tinyTri.size(); i += 3)
        for (int k = 0; k < 3; ++k)
            ++tinyUses[std::minmax(tinyTri[i + k], tinyTri[i + (k + 1) % 3])];
    for (const auto& [edge, n] : tinyUses)
        EXPECT_EQ(n, 2) << "edge " << edge.first << "-" << edge.second << " is not manifold";
    EXPECT_GT(signedVolume(small.positions, tinyTri), 0.0);
}

TEST(Simplify, SheetBoundaryStaysOnTheOriginalBoundaryLine) {
    // A blade-like strip, 1 m x 0.25 m.
    const TestMesh strip = makeGrid(24, 6, 1.0f, 0.25f);
    const SimplifiedMesh s = simplifyMesh(strip.input(), 12);
    EXPECT_LE(s.triangleCount(), 12u);
    const std::vector<uint32_t> tri = originalIndices(s.keptVertices, s.indices);
    auto sides = [&](uint32_t v) {
        const glm::vec3 p = strip.positions[v];
        // Kept vertices are original vertices: their coordinates are exact, no tolerance needed.
        return std::array<bool, 4>{p.x == 0.0f, p.x == 1.0f, p.y == 0.0f, p.y == 0.25f};
    };
    for (const auto& [a, b] : boundaryEdges(tri)) {
        const auto sa = sides(a), sb = sides(b);
        bool common = false;
        for (int k = 0; k < 4; ++k)
            common = common || (sa[k] && sb[k]);
        EXPECT_TRUE(common) << "boundary edge " << a << "-" << b << " leaves the rectangle's outline";
    }
    for (uint32_t corner : {0u, 24u, 150u, 174u})
        EXPECT_TRUE(std::binary_search(s.keptVertices.begin(), s.keptVertices.end(), corner)) << corner;
}

TEST(Simplify, CurvedOutlineKeepsOriginalBoundaryVertices) {
    // A leaf: the strip's half-width follows sqrt(sin(pi s)) along its length, so its outline is
    // curved and cutting it costs.
    TestMesh leaf = makeGrid(30, 4, 1.0f, 1.0f);
    std::set<uint32_t> outline;
    for (uint32_t v = 0; v < leaf.positions.size(); ++v) {
        const glm::vec3 p = leaf.positions[v];
        const float halfWidth = 0.03f * std::max(0.15f, std::sqrt(std::sin(3.14159265f * p.x)));
        leaf.positions[v].y = (p.y - 0.5f) * 2.0f * halfWidth;
        if (p.x == 0.0f || p.x == 1.0f || p.y == 0.0f || p.y == 1.0f)
            outline.insert(v);
    }
    double area = 0.0;
    for (size_t i = 0; i < leaf.indices.size(); i += 3)
        area += 0.5 * glm::length(glm::cross(leaf.positions[leaf.indices[i + 1]] - leaf.positions[leaf.indices[i]],
                                             leaf.positions[leaf.indices[i + 2]] - leaf.positions[leaf.indices[i]]));
    // The rule that a border point only slides along its boundary keeps the outline's vertices
    // on it even with no boundary planes at all (a flat leaf then costs nothing to cave in).
    SimplifyOptions noPlanes;
    noPlanes.boundaryWeight = 0.0f;
    const SimplifiedMesh bare = simplifyMesh(leaf.input(), 24, noPlanes);
    for (const auto& [a, b] : boundaryEdges(originalIndices(bare.keptVertices, bare.indices))) {
        EXPECT_TRUE(outline.count(a)) << a;
        EXPECT_TRUE(outline.count(b)) << b;
    }
    const SimplifiedMesh s = simplifyMesh(leaf.input(), 24);
    const std::vector<uint32_t> tri = originalIndices(s.keptVertices, s.indices);
    for (const auto& [a, b] : boundaryEdges(tri)) {
        EXPECT_TRUE(outline.count(a)) << a;
        EXPECT_TRUE(outline.count(b)) << b;
    }
    double kept = 0.0;
    for (size_t i = 0; i < tri.size(); i += 3)
        kept += 0.5 * glm::length(glm::cross(leaf.positions[tri[i + 1]] - leaf.positions[tri[i]],
                                             leaf.positions[tri[i + 2]] - leaf.positions[tri[i]]));
    // The silhouette shrinks only by chords of the curved outline. 24 triangles leave ~13
    // vertices per side of a profile that rises steeply at both ends: the chords lose ~6 % of the
    // area; 10 % would mean the outline caved in.
    EXPECT_GT(kept / area, 0.9);
}

TEST(Simplify, AttributeWeightKeepsAnAttributeStepLonger) {
    const TestMesh grid = makeGrid(20, 20);
    std::vector<float> step(grid.positions.size());
    for (uint32_t v = 0; v < step.size(); ++v)
        step[v] = column(grid, v) <= 10 ? 0.0f : 1.0f;
    // The plane costs nothing anywhere but at its corners, so without the attribute the order of
    // collapses ignores the step; with it, collapsing across the step costs.
    const uint32_t target = 16;
    SimplifyInput plain = grid.input();
    plain.attributes.push_back({"step", step, 1, 0.0f});
    const SimplifiedMesh without = simplifyMesh(plain, target);
    SimplifyInput weighted = grid.input();
    weighted.attributes.push_back({"step", step, 1, 10.0f});
    const SimplifiedMesh with = simplifyMesh(weighted, target);
    EXPECT_LE(with.triangleCount(), target);
    EXPECT_TRUE(stepIntact(grid, with));
    EXPECT_FALSE(stepIntact(grid, without));
    // And the error reports it: the weighted run pays nothing for the step it kept.
    EXPECT_LT(with.error, 1e-4f);
}

TEST(Simplify, CollapseGroupsKeepVerticesOfDifferentGroupsApart) {
    const TestMesh grid = makeGrid(20, 20);
    std::vector<uint32_t> groups(grid.positions.size());
    for (uint32_t v = 0; v < groups.size(); ++v)
        groups[v] = column(grid, v) <= 10 ? 7 : 9;
    SimplifyInput input = grid.input();
    input.collapseGroups = groups;
    SimplifyOptions options;
    options.allowFallback = false;
    const SimplifiedMesh separate = simplifyMesh(input, 16, options);
    EXPECT_EQ(separate.stage, SimplifyStage::Constrained);
    std::set<uint32_t> keptGroups;
    for (uint32_t v = 0; v < groups.size(); ++v) {
        ASSERT_NE(separate.representative[v], kRemovedVertex);
        EXPECT_EQ(groups[separate.representative[v]], groups[v]) << "vertex " << v;
        keptGroups.insert(groups[separate.representative[v]]);
    }
    EXPECT_EQ(keptGroups.size(), 2u);

    options.separateGroups = false;
    const SimplifiedMesh mixed = simplifyMesh(input, 16, options);
    uint32_t crossed = 0;
    for (uint32_t v = 0; v < groups.size(); ++v)
        crossed += groups[mixed.representative[v]] != groups[v] ? 1 : 0;
    EXPECT_GT(crossed, 0u) << "the grid should collapse across groups when allowed";

    // A checkerboard of groups leaves only the grid's diagonals to collapse along: two triangles
    // are out of reach while groups stay apart, so the fallback's first step relaxes them (and
    // needs no more).
    const TestMesh small = makeGrid(6, 6);
    std::vector<uint32_t> checker(small.positions.size());
    for (uint32_t v = 0; v < checker.size(); ++v)
        checker[v] = (v % 7 + v / 7) % 2;
    SimplifyInput checkered = small.input();
    checkered.collapseGroups = checker;
    SimplifyOptions strict;
    strict.allowFallback = false;
    EXPECT_GT(simplifyMesh(checkered, 2, strict).triangleCount(), 2u) << "groups apart: stuck above 2";
    const SimplifiedMesh relaxed = simplifyMesh(checkered, 2);
    EXPECT_EQ(relaxed.triangleCount(), 2u);
    EXPECT_EQ(relaxed.stage, SimplifyStage::GroupsRelaxed);
    EXPECT_EQ(relaxed.removedComponents, 0u);
}

TEST(Simplify, UvSeamCollapsesAlongItselfBothSidesTogether) {
    const TestMesh tube = makeTube(12, 20);
    const SimplifiedMesh s = simplifyMesh(tube.input(), 60);
    EXPECT_LE(s.triangleCount(), 60u);
    const std::vector<uint32_t> tri = originalIndices(s.keptVertices, s.indices);
    for (size_t i = 0; i < tri.size(); i += 3) {
        const float u0 = tube.uvs[tri[i]].x, u1 = tube.uvs[tri[i + 1]].x, u2 = tube.uvs[tri[i + 2]].x;
        // A triangle next to the seam spans 1/12 of u or a few twelfths; one that mixes the two
        // sides of the seam would span almost 1.
        EXPECT_LT(std::max({u0, u1, u2}) - std::min({u0, u1, u2}), 0.5f) << "triangle " << i / 3;
    }
    // Both wedges of a seam point are kept or neither (columns 0 and 12 of each ring).
    for (uint32_t ring = 0; ring < 20; ++ring) {
        const bool a = std::binary_search(s.keptVertices.begin(), s.keptVertices.end(), ring * 13);
        const bool b = std::binary_search(s.keptVertices.begin(), s.keptVertices.end(), ring * 13 + 12);
        EXPECT_EQ(a, b) << "ring " << ring;
    }
    // No hole: by position, the only boundary left is the two end rings.
    std::map<std::pair<uint32_t, uint32_t>, int> uses;
    auto welded = [](uint32_t v) { return v % 13 == 12 ? v - 12 : v; };
    for (size_t i = 0; i < tri.size(); i += 3)
        for (int k = 0; k < 3; ++k)
            ++uses[std::minmax(welded(tri[i + k]), welded(tri[i + (k + 1) % 3]))];
    for (const auto& [edge, n] : uses) {
        EXPECT_LE(n, 2);
        if (n == 1) {
            const float y0 = tube.positions[edge.first].y, y1 = tube.positions[edge.second].y;
            EXPECT_TRUE((y0 == 0.0f && y1 == 0.0f) || (y0 == 1.0f && y1 == 1.0f)) << edge.first << "-" << edge.second;
        }
    }
}

TEST(Simplify, ThinTubeIsNeverPinched) {
    // A three-sided tube: every ring vertex neighbours both others of its ring, the configuration
    // where collapsing a ring edge would pinch the tube to a non-manifold edge (link condition).
    const TestMesh tube = makeTube(3, 12);
    SimplifyOptions options;
    options.allowFallback = false;
    const SimplifiedMesh s = simplifyMesh(tube.input(), 1, options);
    const std::vector<uint32_t> tri = originalIndices(s.keptVertices, s.indices);
    std::map<std::pair<uint32_t, uint32_t>, int> uses;
    auto welded = [](uint32_t v) { return v % 4 == 3 ? v - 3 : v; };
    for (size_t i = 0; i < tri.size(); i += 3)
        for (int k = 0; k < 3; ++k)
            ++uses[std::minmax(welded(tri[i + k]), welded(tri[i + (k + 1) % 3]))];
    for (const auto& [edge, n] : uses)
        EXPECT_LE(n, 2) << "edge " << edge.first << "-" << edge.second << " is not manifold";
    EXPECT_GE(s.triangleCount(), 6u); // a triangular prism at least
}

TEST(Simplify, OutputReferencesKeptOriginalVerticesOnly) {
    const IrisCase& iris = irisCase("ci");
    const uint32_t n = uint32_t(iris.clump.mesh.vertexCount()), full = uint32_t(iris.clump.mesh.triangleCount());
    MeshSimplifier simplifier(iris.input());
    for (uint32_t target : {full / 3, full / 10, full / 40, full / 150}) {
        const SimplifiedMesh s = simplifier.simplifyTo(target);
        ASSERT_FALSE(s.keptVertices.empty());
        for (size_t i = 1; i < s.keptVertices.size(); ++i)
            ASSERT_LT(s.keptVertices[i - 1], s.keptVertices[i]) << "kept vertices must be unique and ascending";
        ASSERT_LT(s.keptVertices.back(), n);
        std::vector<uint8_t> used(s.keptVertices.size(), 0);
        for (uint32_t index : s.indices) {
            ASSERT_LT(index, s.keptVertices.size());
            used[index] = 1;
        }
        EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](uint8_t u) { return u == 1; })) << "unused kept vertex";
        ASSERT_EQ(s.representative.size(), n);
        for (uint32_t v = 0; v < n; ++v) {
            const uint32_t r = s.representative[v];
            if (r != kRemovedVertex) {
                EXPECT_TRUE(std::binary_search(s.keptVertices.begin(), s.keptVertices.end(), r)) << v;
            }
        }
        for (uint32_t k : s.keptVertices)
            EXPECT_EQ(s.representative[k], k);
    }
}

TEST(Simplify, SameInputGivesTheSameBytes) {
    const IrisCase& iris = irisCase("ci");
    const uint32_t target = uint32_t(iris.clump.mesh.triangleCount() / 10);
    const SimplifiedMesh a = simplifyMesh(iris.input(), target), b = simplifyMesh(iris.input(), target);
    EXPECT_EQ(a.keptVertices, b.keptVertices);
    EXPECT_EQ(a.indices, b.indices);
    EXPECT_EQ(a.representative, b.representative);
    EXPECT_EQ(std::memcmp(&a.error, &b.error, sizeof(float)), 0);
}

TEST(Simplify, FallbackRemovesSmallComponentsOnlyWhenAllowed) {
    // Three separate flat quads, 1, 2 and 3 m wide: no collapse can take a component below one
    // triangle, so one triangle is out of reach without removing components.
    TestMesh quads;
    for (uint32_t q = 0; q < 3; ++q) {
        const float size = float(q + 1), offset = 10.0f * float(q);
        const uint32_t base = uint32_t(quads.positions.size());
        for (glm::vec2 c : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
            quads.positions.emplace_back(offset + c.x * size, c.y * size, 0.0f);
            quads.normals.emplace_back(0.0f, 0.0f, 1.0f);
            quads.uvs.push_back(c);
        }
        quads.indices.insert(quads.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    SimplifyOptions strict;
    strict.allowFallback = false;
    const SimplifiedMesh stopped = simplifyMesh(quads.input(), 1, strict);
    EXPECT_EQ(stopped.triangleCount(), 3u);
    EXPECT_EQ(stopped.stage, SimplifyStage::Constrained);

    const SimplifiedMesh removed = simplifyMesh(quads.input(), 1);
    EXPECT_EQ(removed.triangleCount(), 1u);
    EXPECT_EQ(removed.stage, SimplifyStage::ComponentsRemoved);
    EXPECT_EQ(removed.removedComponents, 2u);
    for (uint32_t v : removed.keptVertices)
        EXPECT_GE(v, 8u) << "the largest quad (vertices 8..11) is the one to keep";
    for (uint32_t v = 0; v < 8; ++v)
        EXPECT_EQ(removed.representative[v], kRemovedVertex);
}

TEST(Simplify, RejectsBadInput) {
    const TestMesh grid = makeGrid(2, 2);
    auto run = [&](auto&& edit, uint32_t target = 2) {
        TestMesh copy = grid;
        SimplifyInput input = copy.input();
        std::vector<float> values(copy.positions.size(), 0.0f);
        std::vector<uint32_t> groups;
        edit(copy, input, values, groups);
        input.positions = copy.positions;
        input.indices = copy.indices;
        simplifyMesh(input, target);
    };
    auto none = [](TestMesh&, SimplifyInput&, std::vector<float>&, std::vector<uint32_t>&) {};
    expectError([&] { run(none, 0); }, "simplify: the target triangle count is 0");
    expectError([&] { run([](TestMesh& m, auto&, auto&, auto&) { m.indices[4] = 9; }); },
                "simplify: index 4 (triangle 1) is 9, the mesh has 9 vertices");
    expectError([&] { run([](TestMesh& m, auto&, auto&, auto&) { m.indices.pop_back(); }); },
                "index count 23 is not a multiple of 3");
    expectError([&] { run([](TestMesh& m, auto&, auto&, auto&) { m.positions[3].y = std::nanf(""); }); },
                "the position of vertex 3 is not finite");
    expectError([&] { run([](TestMesh&, SimplifyInput& in, auto&, auto&) { in.normals = in.normals.first(5); }); },
                "5 normals for 9 positions");
    expectError(
        [&] {
            run([](TestMesh&, SimplifyInput& in, std::vector<float>& v, auto&) {
                in.attributes.push_back({"light", std::span<const float>(v).first(8), 1, 1.0f});
            });
        },
        "attribute group 'light' holds 8 values, expected 9 vertices x 1");
    expectError(
        [&] {
            run([](TestMesh&, SimplifyInput& in, std::vector<float>& v, auto&) {
                v[2] = INFINITY;
                in.attributes.push_back({"motion", v, 1, 1.0f});
            });
        },
        "attribute group 'motion' value 0 of vertex 2 is not finite");
    expectError(
        [&] {
            run([](TestMesh&, SimplifyInput& in, std::vector<float>& v, auto&) {
                in.attributes.push_back({"light", v, 1, -1.0f});
            });
        },
        "attribute group 'light' has weight -1");
    expectError(
        [&] {
            run([](TestMesh&, SimplifyInput& in, auto&, std::vector<uint32_t>& g) {
                g.assign(4, 0);
                in.collapseGroups = g;
            });
        },
        "4 collapse groups for 9 positions");
    expectError([&] { run([](TestMesh& m, auto&, auto&, auto&) { m.indices.clear(); }); }, "no triangles");
}
