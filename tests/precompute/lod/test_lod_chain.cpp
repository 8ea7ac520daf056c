// Five LODs of real iris clumps (precompute/lod/lod_chain.cpp): budgets, validity of every
// triangle, nesting, and the meshoptimizer ordering.
#include "lod_fixtures.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

using namespace meadow;
using namespace meadow::test;

namespace {

struct Built {
    std::array<MeshLod, kLodCount> lods;
};

const Built& built(const std::string& preset) {
    static std::map<std::string, Built> cache;
    auto it = cache.find(preset);
    if (it == cache.end())
        it = cache.emplace(preset, Built{buildLods(irisCase(preset).input())}).first;
    return it->second;
}

class IrisLods : public ::testing::TestWithParam<const char*> {};

} // namespace

TEST_P(IrisLods, BudgetsAreMet) {
    const IrisCase& iris = irisCase(GetParam());
    const std::array<MeshLod, kLodCount>& lods = built(GetParam()).lods;
    const LodOptions defaults;
    const double full = double(iris.clump.mesh.triangleCount());
    for (uint32_t i = 0; i < kLodCount; ++i) {
        const MeshLod& lod = lods[i];
        const uint32_t target = uint32_t(std::max(1.0, std::round(defaults.triangleFractions[i] * full)));
        EXPECT_EQ(lod.targetTriangles, target);
        EXPECT_LE(lod.triangleCount(), target) << "LOD " << i;
        // A collapse removes at most a few triangles, so the loop stops within 4 of the target.
        // When the fallback removes whole components the last one may go below it by up to a
        // stem tube's worth (~10-20 triangles): 10 % of the target, or 4.
        const uint32_t slack = lod.stage == SimplifyStage::ComponentsRemoved ? std::max(4u, target / 10) : 4u;
        EXPECT_GE(lod.triangleCount() + slack, target) << "LOD " << i;
        std::printf("[ lod %s ] LOD %u: %u triangles (target %u), %zu vertices, error %.4f m, stage %d, removed %u, "
                    "ACMR %.3f\n",
                    GetParam(), i, lod.triangleCount(), target, lod.vertices.size(), lod.error, int(lod.stage),
                    lod.removedComponents, lod.acmr);
    }
    EXPECT_EQ(lods[0].triangleCount(), uint32_t(full)) << "LOD 0 is the full mesh";
}

TEST_P(IrisLods, NoDegenerateOrFlippedTriangles) {
    const IrisCase& iris = irisCase(GetParam());
    const std::vector<glm::vec3>& p = iris.clump.mesh.positions;
    const std::vector<glm::vec3> surface = surfaceNormals(p, iris.clump.mesh.indices);
    for (uint32_t i = 0; i < kLodCount; ++i) {
        const std::vector<uint32_t> tri =
            originalIndices(built(GetParam()).lods[i].vertices, built(GetParam()).lods[i].indices);
        uint32_t degenerate = 0, flipped = 0;
        for (size_t t = 0; t < tri.size(); t += 3) {
            const glm::vec3 a = p[tri[t]], b = p[tri[t + 1]], c = p[tri[t + 2]];
            const glm::vec3 n = glm::cross(b - a, c - a);
            const float longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
            // Zero area, or a height below 1e-4 of the longest edge (the simplifier rejects 1e-3).
            if (!(glm::length(n) > 1e-4f * longest * longest))
                ++degenerate;
            // Flipped: facing away from the original surface at its own corners.
            if (!(glm::dot(n, surface[tri[t]] + surface[tri[t + 1]] + surface[tri[t + 2]]) > 0.0f))
                ++flipped;
        }
        EXPECT_EQ(degenerate, 0u) << "LOD " << i;
        EXPECT_EQ(flipped, 0u) << "LOD " << i;
    }
}

TEST_P(IrisLods, CoarserLodsKeepASubsetOfTheVertices) {
    const std::array<MeshLod, kLodCount>& lods = built(GetParam()).lods;
    for (uint32_t i = 1; i < kLodCount; ++i) {
        std::vector<uint32_t> finer = lods[i - 1].vertices, coarser = lods[i].vertices;
        std::sort(finer.begin(), finer.end());
        std::sort(coarser.begin(), coarser.end());
        EXPECT_TRUE(std::adjacent_find(coarser.begin(), coarser.end()) == coarser.end()) << "duplicate vertex";
        EXPECT_TRUE(std::includes(finer.begin(), finer.end(), coarser.begin(), coarser.end())) << "LOD " << i;
        EXPECT_LT(coarser.size(), finer.size());
    }
}

TEST_P(IrisLods, OrderedForTheVertexCacheAndForFetch) {
    const IrisCase& iris = irisCase(GetParam());
    // The same collapse sequence before optimisation: the simplifier's own triangle order.
    MeshSimplifier simplifier(iris.input());
    for (const MeshLod& lod : built(GetParam()).lods) {
        // Fetch order: vertices appear in the index buffer in the order they are stored.
        uint32_t next = 0;
        for (uint32_t index : lod.indices) {
            ASSERT_LE(index, next);
            if (index == next)
                ++next;
        }
        EXPECT_EQ(next, lod.vertices.size());

        const SimplifiedMesh raw = simplifier.simplifyTo(lod.targetTriangles);
        ASSERT_EQ(raw.indices.size(), lod.indices.size());
        auto acmr = [&](const std::vector<uint32_t>& indices) {
            return meshopt_analyzeVertexCache(indices.data(), indices.size(), raw.keptVertices.size(), 16, 0, 0).acmr;
        };
        // The same triangles in a scrambled order (a fixed odd stride through the list).
        std::vector<uint32_t> scrambled;
        const size_t triangles = raw.indices.size() / 3;
        for (size_t i = 0, t = 0; i < triangles; ++i, t = (t + 7919) % triangles)
            scrambled.insert(scrambled.end(), raw.indices.begin() + 3 * t, raw.indices.begin() + 3 * t + 3);
        // Optimised: never meaningfully worse than the generator's row-by-row order, which is
        // already close to optimal for grids (meshoptimizer's model is not the 16-entry FIFO
        // measured here: 1 % either way), and much better than scrambled where there is reuse to
        // find: fewer than 1.5 vertices per triangle (far LODs are separate single triangles,
        // 3 misses each in any order).
        EXPECT_LE(lod.acmr, acmr(raw.indices) * 1.01f);
        if (lod.vertices.size() < 1.5 * lod.triangleCount()) {
            EXPECT_LT(lod.acmr, acmr(scrambled) * 0.75f);
        }
    }
    // The full clump is made of regular grids: well below 1 miss per triangle once optimised
    // (meshoptimizer reaches ~0.6-0.7 on such meshes; 1.0 leaves room for the small pieces).
    EXPECT_LT(built(GetParam()).lods[0].acmr, 1.0f);
}

// The area term (SimplifyOptions::areaWeight): without it a blade or petal loses its tip at no
// quadric cost. With it no LOD of 1-3 keeps less of the clump's surface, and together they keep
// more. On this fixture's clump (its attributes are synthetic) the gain is smaller than on the
// libraries' clumps: +0.012 / +0.044 / +0.011 (ci) and +0.017 / +0.035 / +0.012 (full); the
// libraries' figures are checked by cli.precompute_inspect.
TEST_P(IrisLods, TheAreaTermKeepsTheSurface) {
    const IrisCase& iris = irisCase(GetParam());
    const std::vector<glm::vec3>& p = iris.clump.mesh.positions;
    auto area = [&](const MeshLod& lod) {
        const std::vector<uint32_t> tri = originalIndices(lod.vertices, lod.indices);
        double sum = 0.0;
        for (size_t t = 0; t < tri.size(); t += 3)
            sum += 0.5 * glm::length(
                             glm::cross(glm::dvec3(p[tri[t + 1]] - p[tri[t]]), glm::dvec3(p[tri[t + 2]] - p[tri[t]])));
        return sum;
    };
    LodOptions without;
    without.simplify.areaWeight = 0.0f;
    const std::array<MeshLod, kLodCount> plain = buildLods(iris.input(), without);
    const std::array<MeshLod, kLodCount>& lods = built(GetParam()).lods;
    const double full = area(lods[0]);
    double gain = 0.0;
    for (uint32_t i = 1; i <= 3; ++i) {
        const double kept = area(lods[i]) / full, keptWithout = area(plain[i]) / full;
        std::printf("[ lod %s ] LOD %u keeps %.3f of the area (%.3f without the area term)\n", GetParam(), i, kept,
                    keptWithout);
        EXPECT_GE(kept, keptWithout) << "LOD " << i;
        gain += kept - keptWithout;
    }
    EXPECT_GE(gain, 0.05);
}

INSTANTIATE_TEST_SUITE_P(Presets, IrisLods, ::testing::Values("ci", "full"));

TEST(LodChain, RejectsBadFractions) {
    const TestMesh grid = makeGrid(4, 4);
    LodOptions options;
    options.triangleFractions[2] = 0.0f;
    try {
        buildLods(grid.input(), options);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("LOD: the triangle fraction of LOD 2 is 0"), std::string::npos)
            << e.what();
    }
    options.triangleFractions = {1.0f, 0.2f, 0.5f, 0.1f, 0.05f};
    try {
        buildLods(grid.input(), options);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("LOD 2 (0.5"), std::string::npos) << e.what();
    }
}

TEST(LodChain, SameInputGivesTheSameBytes) {
    const IrisCase& iris = irisCase("ci");
    const std::array<MeshLod, kLodCount> a = buildLods(iris.input()), b = buildLods(iris.input());
    for (uint32_t i = 0; i < kLodCount; ++i) {
        EXPECT_EQ(a[i].vertices, b[i].vertices);
        EXPECT_EQ(a[i].indices, b[i].indices);
        EXPECT_EQ(a[i].error, b[i].error);
    }
}
