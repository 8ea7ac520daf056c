// Procedural iris clumps (precompute/plants/iris.h): determinism, plant anatomy, mesh validity,
// skinning and the triangle budget of each preset.
#include "core/error.h"
#include "plants/atlas.h"
#include "plants/iris.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <map>
#include <numeric>

namespace meadow {
namespace {

constexpr uint64_t kSeed = 20040807;

const std::vector<PlantClump>& ciClumps() {
    static const std::vector<PlantClump> clumps = makeIrisClumps(kSeed, 4, irisParamsForPreset("ci"));
    return clumps;
}
const std::vector<PlantClump>& fullClumps() {
    static const std::vector<PlantClump> clumps = makeIrisClumps(kSeed, 4, irisParamsForPreset("full"));
    return clumps;
}
std::vector<const PlantClump*> allClumps() {
    std::vector<const PlantClump*> all;
    for (const PlantClump& c : ciClumps())
        all.push_back(&c);
    for (const PlantClump& c : fullClumps())
        all.push_back(&c);
    return all;
}

template <typename T> bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool identical(const PlantClump& a, const PlantClump& b) {
    if (a.name != b.name || a.plants != b.plants || a.rods.size() != b.rods.size())
        return false;
    const PlantMesh& m = a.mesh;
    const PlantMesh& n = b.mesh;
    if (!sameBytes(m.positions, n.positions) || !sameBytes(m.normals, n.normals) || !sameBytes(m.uvs, n.uvs) ||
        !sameBytes(m.indices, n.indices) || !sameBytes(m.parts, n.parts) || m.skin.size() != n.skin.size())
        return false;
    for (size_t i = 0; i < m.skin.size(); ++i)
        if (m.skin[i].rod != n.skin[i].rod || m.skin[i].segment != n.skin[i].segment || m.skin[i].t != n.skin[i].t ||
            m.skin[i].offset != n.skin[i].offset)
            return false;
    for (size_t r = 0; r < a.rods.size(); ++r) {
        const Rod& x = a.rods[r];
        const Rod& y = b.rods[r];
        if (x.kind != y.kind || x.plant != y.plant || !sameBytes(x.restNodes, y.restNodes) ||
            !sameBytes(x.width, y.width) || x.thickness != y.thickness || x.tipMass != y.tipMass ||
            !sameBytes(x.nodeMass, y.nodeMass))
            return false;
    }
    return true;
}

// Connected pieces of the mesh per (plant, part): each petal, leaf and tube is one sheet of
// shared vertices, so counting components counts petals without trusting the generator.
std::map<std::pair<uint32_t, PartKind>, uint32_t> pieces(const PlantClump& clump) {
    const PlantMesh& mesh = clump.mesh;
    std::vector<uint32_t> parent(mesh.positions.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t x) {
        while (parent[x] != x)
            x = parent[x] = parent[parent[x]];
        return x;
    };
    for (size_t i = 0; i < mesh.indices.size(); i += 3)
        for (int k = 1; k < 3; ++k)
            parent[find(mesh.indices[i + k])] = find(mesh.indices[i]);
    std::map<std::pair<uint32_t, PartKind>, uint32_t> counts;
    for (uint32_t v = 0; v < mesh.positions.size(); ++v)
        if (find(v) == v)
            ++counts[{clump.rods[mesh.skin[v].rod].plant, mesh.parts[v]}];
    return counts;
}

TEST(Iris, SameSeedGivesIdenticalClumps) {
    std::vector<PlantClump> again = makeIrisClumps(kSeed, 4, irisParamsForPreset("ci"));
    ASSERT_EQ(again.size(), 4u);
    for (size_t i = 0; i < 4; ++i)
        EXPECT_TRUE(identical(again[i], ciClumps()[i])) << "clump " << i;
}

TEST(Iris, ClumpDependsOnSeedAndIndexOnly) {
    std::vector<PlantClump> other = makeIrisClumps(kSeed + 1, 4, irisParamsForPreset("ci"));
    for (size_t i = 0; i < 4; ++i)
        EXPECT_FALSE(identical(other[i], ciClumps()[i])) << "clump " << i;
    for (size_t i = 1; i < 4; ++i)
        EXPECT_FALSE(identical(ciClumps()[0], ciClumps()[i])) << "clump " << i;
    // Asking for fewer clumps gives the same first ones.
    std::vector<PlantClump> two = makeIrisClumps(kSeed, 2, irisParamsForPreset("ci"));
    EXPECT_TRUE(identical(two[1], ciClumps()[1]));
    EXPECT_EQ(ciClumps()[2].name, "iris-clump-2");
}

TEST(Iris, PresetsAndParametersAreChecked) {
    EXPECT_THROW(irisParamsForPreset("huge"), Error);
    IrisParams bad = irisParamsForPreset("ci");
    bad.leafColumns = 4; // no vertex on the midrib
    EXPECT_THROW(makeIrisClumps(1, 1, bad), Error);
    bad = irisParamsForPreset("ci");
    bad.stemNodes = 2;
    EXPECT_THROW(makeIrisClumps(1, 1, bad), Error);
}

TEST(Iris, SixOrSevenIrisesPerClump) {
    for (uint64_t seed = 1; seed <= 6; ++seed)
        for (const PlantClump& clump : makeIrisClumps(seed, 4, irisParamsForPreset("ci"))) {
            EXPECT_GE(clump.plants, 6u);
            EXPECT_LE(clump.plants, 7u);
        }
}

TEST(Iris, EveryIrisHasLeavesAStemAndWholeFlowers) {
    for (const PlantClump* clump : allClumps()) {
        auto counts = pieces(*clump);
        for (uint32_t plant = 0; plant < clump->plants; ++plant) {
            uint32_t leafRods = 0, stemRods = 0;
            for (const Rod& rod : clump->rods)
                if (rod.plant == plant)
                    (rod.kind == RodKind::Leaf ? leafRods : stemRods)++;
            SCOPED_TRACE(clump->name + " plant " + std::to_string(plant));
            EXPECT_GE(leafRods, 5u);
            EXPECT_LE(leafRods, 8u);
            EXPECT_EQ(stemRods, 1u);
            EXPECT_EQ((counts[{plant, PartKind::Leaf}]), leafRods);
            // One or two flowers: the second sits on its own pedicel, a second stem piece.
            uint32_t flowers = counts[{plant, PartKind::Stem}];
            EXPECT_GE(flowers, 1u);
            EXPECT_LE(flowers, 2u);
            EXPECT_EQ((counts[{plant, PartKind::Fall}]), 3 * flowers);
            EXPECT_EQ((counts[{plant, PartKind::Standard}]), 3 * flowers);
            EXPECT_EQ((counts[{plant, PartKind::StyleArm}]), 3 * flowers);
            EXPECT_EQ((counts[{plant, PartKind::Other}]), 0u);
        }
    }
}

TEST(Iris, LeafAndStemDimensions) {
    for (const PlantClump* clump : allClumps()) {
        std::vector<float> leafTop(clump->plants, 0.0f), stemTop(clump->plants, 0.0f);
        for (const Rod& rod : clump->rods) {
            EXPECT_GE(rod.restNodes.size(), 6u);
            EXPECT_LE(rod.restNodes.size(), 12u);
            // Node 0 is anchored at the rhizome.
            EXPECT_NEAR(rod.restNodes[0].y, 0.0f, 0.01f);
            float length = rodLength(rod);
            float top = 0.0f;
            for (const glm::vec3& n : rod.restNodes)
                top = std::max(top, n.y);
            float widest = *std::max_element(rod.width.begin(), rod.width.end());
            if (rod.kind == RodKind::Leaf) {
                EXPECT_GE(length, 0.4f);
                EXPECT_LE(length, 0.9f);
                EXPECT_GE(widest, 0.02f * 0.999f);
                EXPECT_LE(widest, 0.04f * 1.001f);
                EXPECT_EQ(rod.tipMass, 0.0f);
                leafTop[rod.plant] = std::max(leafTop[rod.plant], top);
            } else {
                EXPECT_GE(length, 0.5f);
                EXPECT_LE(length, 0.9f);
                EXPECT_GT(rod.tipMass, 0.0f);
                stemTop[rod.plant] = top;
            }
        }
        // The flower stem rises above the fan.
        for (uint32_t plant = 0; plant < clump->plants; ++plant)
            EXPECT_GT(stemTop[plant], leafTop[plant]) << clump->name << " plant " << plant;
    }
}

TEST(Iris, MeshIsValid) {
    for (const PlantClump* clump : allClumps()) {
        SCOPED_TRACE(clump->name);
        EXPECT_NO_THROW(checkPlantClump(*clump, clump->name));
        const PlantMesh& mesh = clump->mesh;
        // Normals are unit length; 1e-4 allows float rounding of the normalisation.
        for (const glm::vec3& n : mesh.normals)
            ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
        // The thinnest triangles (style arm ends, leaf tips) are several square millimetres;
        // 0.1 mm² flags only triangles that collapsed.
        for (size_t i = 0; i < mesh.indices.size(); i += 3) {
            glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                      c = mesh.positions[mesh.indices[i + 2]];
            ASSERT_GT(0.5f * glm::length(glm::cross(b - a, c - a)), 1e-7f) << "triangle " << i / 3;
        }
    }
}

TEST(Iris, SkinBindingsReproduceRestPositions) {
    for (const PlantClump* clump : allClumps()) {
        const PlantMesh& mesh = clump->mesh;
        for (size_t v = 0; v < mesh.positions.size(); ++v) {
            const SkinBinding& b = mesh.skin[v];
            // 1e-5 m: the offset is computed from the same float operations, so only rounding of
            // positions up to ~1 m separates them.
            float error = glm::length(boundRestPosition(clump->rods, b) - mesh.positions[v]);
            ASSERT_LT(error, 1e-5f) << clump->name << " vertex " << v;
            const Rod& rod = clump->rods[b.rod];
            PartKind part = mesh.parts[v];
            RodKind expected = part == PartKind::Leaf ? RodKind::Leaf : RodKind::Stem;
            ASSERT_EQ(rod.kind, expected) << clump->name << " vertex " << v;
            // Flowers ride rigidly on a stem node.
            bool flower = part == PartKind::Fall || part == PartKind::Standard || part == PartKind::StyleArm;
            if (flower) {
                ASSERT_EQ(b.t, 1.0f) << clump->name << " vertex " << v;
            }
        }
    }
}

TEST(Iris, UvsLieInTheirPartsRegion) {
    for (const PlantClump* clump : allClumps()) {
        const PlantMesh& mesh = clump->mesh;
        for (size_t v = 0; v < mesh.positions.size(); ++v)
            ASSERT_TRUE(irisAtlasRegion(mesh.parts[v]).contains(mesh.uvs[v]))
                << clump->name << " vertex " << v << " uv " << mesh.uvs[v].x << "," << mesh.uvs[v].y;
    }
}

TEST(Iris, IrisesGrowInCloseContact) {
    for (const PlantClump* clump : allClumps()) {
        std::vector<glm::vec3> rhizomes(clump->plants);
        std::vector<glm::vec2> lo(clump->plants, glm::vec2(1e9f)), hi(clump->plants, glm::vec2(-1e9f));
        for (const Rod& rod : clump->rods) {
            if (rod.kind == RodKind::Stem)
                rhizomes[rod.plant] = rod.restNodes[0];
            for (const glm::vec3& n : rod.restNodes) {
                lo[rod.plant] = glm::min(lo[rod.plant], glm::vec2(n.x, n.z));
                hi[rod.plant] = glm::max(hi[rod.plant], glm::vec2(n.x, n.z));
            }
        }
        for (uint32_t p = 0; p < clump->plants; ++p) {
            float nearest = 1e9f;
            bool overlaps = false;
            for (uint32_t q = 0; q < clump->plants; ++q) {
                if (q == p)
                    continue;
                nearest = std::min(nearest, glm::length(rhizomes[p] - rhizomes[q]));
                overlaps |= glm::all(glm::lessThan(lo[p], hi[q])) && glm::all(glm::lessThan(lo[q], hi[p]));
            }
            // A few centimetres apart: close enough to touch, far enough not to share a rhizome.
            EXPECT_LT(nearest, 0.1f) << clump->name << " plant " << p;
            EXPECT_GT(nearest, 0.03f) << clump->name << " plant " << p;
            EXPECT_TRUE(overlaps) << clump->name << " plant " << p << "'s fan overlaps no other";
        }
    }
}

TEST(Iris, TriangleBudgetPerPreset) {
    for (uint64_t seed = 1; seed <= 4; ++seed) {
        std::vector<PlantClump> full = makeIrisClumps(seed, 4, irisParamsForPreset("full"));
        std::vector<PlantClump> ci = makeIrisClumps(seed, 4, irisParamsForPreset("ci"));
        for (size_t i = 0; i < 4; ++i) {
            size_t fullTriangles = full[i].mesh.triangleCount();
            size_t ciTriangles = ci[i].mesh.triangleCount();
            SCOPED_TRACE("seed " + std::to_string(seed) + " " + full[i].name);
            EXPECT_GE(fullTriangles, 3000u);
            EXPECT_LE(fullTriangles, 8000u);
            // "About a third": the same plants, coarser.
            double ratio = static_cast<double>(ciTriangles) / static_cast<double>(fullTriangles);
            EXPECT_GT(ratio, 0.2);
            EXPECT_LT(ratio, 0.45);
        }
    }
}

} // namespace
} // namespace meadow
