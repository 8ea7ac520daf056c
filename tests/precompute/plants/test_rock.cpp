// Procedural rocks (precompute/plants/rock.h): determinism, size, the cut at the ground,
// watertightness above ground, and unit outward normals.
#include "core/error.h"
#include "plants/rock.h"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <map>
#include <utility>

namespace meadow {
namespace {

constexpr uint64_t kSeed = 20040807;

const std::vector<RockMesh>& fullRocks() {
    static const std::vector<RockMesh> rocks = makeRocks(kSeed, 6, rockParamsForPreset("full"));
    return rocks;
}

template <typename T> bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool identical(const RockMesh& a, const RockMesh& b) {
    return a.name == b.name && a.size == b.size && sameBytes(a.positions, b.positions) &&
           sameBytes(a.normals, b.normals) && sameBytes(a.uvs, b.uvs) && sameBytes(a.indices, b.indices);
}

TEST(Rock, Deterministic) {
    const std::vector<RockMesh> again = makeRocks(kSeed, 6, rockParamsForPreset("full"));
    for (size_t i = 0; i < again.size(); ++i)
        EXPECT_TRUE(identical(fullRocks()[i], again[i])) << "rock " << i;
    // Rock i depends on the seed and i only, not on how many are made.
    const std::vector<RockMesh> fewer = makeRocks(kSeed, 2, rockParamsForPreset("full"));
    EXPECT_TRUE(identical(fullRocks()[1], fewer[1]));
    const std::vector<RockMesh> other = makeRocks(kSeed + 1, 2, rockParamsForPreset("full"));
    EXPECT_FALSE(identical(fullRocks()[0], other[0]));
    // Variants differ from one another.
    EXPECT_FALSE(sameBytes(fullRocks()[0].positions, fullRocks()[1].positions));
}

TEST(Rock, SizeAndPlacementOnTheGround) {
    for (const RockMesh& rock : fullRocks()) {
        SCOPED_TRACE(rock.name);
        ASSERT_EQ(rock.normals.size(), rock.positions.size());
        ASSERT_EQ(rock.uvs.size(), rock.positions.size());
        ASSERT_EQ(rock.indices.size() % 3, 0u);
        EXPECT_GE(rock.size, 0.2f);
        EXPECT_LE(rock.size, 0.6f);
        glm::vec3 lo = rock.positions[0], hi = lo;
        for (const glm::vec3& p : rock.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        // The mesh is scaled to its size: float rounding of one multiply and subtract.
        EXPECT_NEAR(std::max(hi.x - lo.x, hi.z - lo.z), rock.size, 1e-5f * rock.size);
        EXPECT_EQ(lo.y, 0.0f); // the cut rim lies exactly on the ground
        // Squashed: lower than wide, and not a sliver either.
        EXPECT_GT(hi.y, 0.1f * rock.size);
        EXPECT_LT(hi.y, rock.size);
        // The footprint is centred: |x|, |z| <= size / 2 (+ rounding of one subtract and multiply).
        for (const glm::vec3& p : rock.positions) {
            EXPECT_LE(std::abs(p.x), 0.5f * rock.size + 1e-5f);
            EXPECT_LE(std::abs(p.z), 0.5f * rock.size + 1e-5f);
        }
        for (const glm::vec2& uv : rock.uvs) {
            EXPECT_GE(uv.x, 0.0f);
            EXPECT_LE(uv.x, 1.0f);
            EXPECT_GE(uv.y, 0.0f);
            EXPECT_LE(uv.y, 1.0f);
        }
    }
}

TEST(Rock, WatertightAboveGround) {
    for (const RockMesh& rock : fullRocks()) {
        SCOPED_TRACE(rock.name);
        // Directed edges: inside the surface each edge appears once in each direction (two
        // triangles, consistent winding); a cut edge appears once and lies on y = 0.
        std::map<std::pair<uint32_t, uint32_t>, int> directed;
        for (size_t i = 0; i < rock.indices.size(); i += 3)
            for (int k = 0; k < 3; ++k)
                ++directed[{rock.indices[i + size_t(k)], rock.indices[i + size_t((k + 1) % 3)]}];
        std::map<uint32_t, int> rimBalance; // out minus in along the rim: 0 everywhere for closed loops
        size_t rimEdges = 0;
        for (const auto& [edge, count] : directed) {
            EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " is used twice in one direction";
            if (directed.count({edge.second, edge.first}))
                continue;
            EXPECT_EQ(rock.positions[edge.first].y, 0.0f) << "open edge above ground";
            EXPECT_EQ(rock.positions[edge.second].y, 0.0f) << "open edge above ground";
            ++rimBalance[edge.first];
            --rimBalance[edge.second];
            ++rimEdges;
        }
        EXPECT_GE(rimEdges, 6u); // half-buried: there is a rim
        for (const auto& [vertex, balance] : rimBalance)
            EXPECT_EQ(balance, 0) << "the rim is not a closed loop at vertex " << vertex;
        // No degenerate triangle: the cut can make slivers, never zero-area ones (1e-12 m^2 is
        // far below any real triangle of a 0.2 m rock at 3 subdivisions, ~1e-4 m^2).
        for (size_t i = 0; i < rock.indices.size(); i += 3) {
            const glm::vec3 a = rock.positions[rock.indices[i]], b = rock.positions[rock.indices[i + 1]],
                            c = rock.positions[rock.indices[i + 2]];
            EXPECT_GT(glm::length(glm::cross(b - a, c - a)), 2e-12f);
        }
    }
}

TEST(Rock, NormalsUnitAndOutward) {
    for (const RockMesh& rock : fullRocks()) {
        SCOPED_TRACE(rock.name);
        std::vector<glm::vec3> faceSum(rock.positions.size(), glm::vec3(0.0f));
        double volume = 0.0;
        for (size_t i = 0; i < rock.indices.size(); i += 3) {
            const uint32_t ia = rock.indices[i], ib = rock.indices[i + 1], ic = rock.indices[i + 2];
            const glm::dvec3 a(rock.positions[ia]), b(rock.positions[ib]), c(rock.positions[ic]);
            const glm::dvec3 areaNormal = 0.5 * glm::cross(b - a, c - a);
            // Divergence theorem with the field (0, y, 0): volume = sum over faces of mean y times
            // the face's area-weighted normal y; the ground (y = 0) closing the surface adds 0.
            volume += (a.y + b.y + c.y) / 3.0 * areaNormal.y;
            for (uint32_t v : {ia, ib, ic})
                faceSum[v] += glm::vec3(areaNormal);
        }
        // Outward winding encloses a positive volume, and a sizeable one: more than 1 % of the
        // bounding box (a half-buried squashed blob fills roughly a third of it).
        glm::vec3 lo = rock.positions[0], hi = lo;
        for (const glm::vec3& p : rock.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        EXPECT_GT(volume, 0.01 * double(hi.x - lo.x) * double(hi.y - lo.y) * double(hi.z - lo.z));
        for (size_t v = 0; v < rock.normals.size(); ++v) {
            // Unit: normalised floats, within a few ulps.
            EXPECT_NEAR(glm::length(rock.normals[v]), 1.0f, 1e-5f) << "vertex " << v;
            // Outward: on the side of the faces around the vertex (which wind outward). The
            // surface is smooth at this tessellation, so the two agree well within 90 degrees.
            EXPECT_GT(glm::dot(rock.normals[v], glm::normalize(faceSum[v])), 0.5f) << "vertex " << v;
        }
    }
}

TEST(Rock, CiPresetIsCoarser) {
    const std::vector<RockMesh> ci = makeRocks(kSeed, 1, rockParamsForPreset("ci"));
    EXPECT_LT(ci[0].indices.size(), fullRocks()[0].indices.size());
    EXPECT_GT(ci[0].indices.size(), 3u * 40u);
}

TEST(Rock, BadParameters) {
    EXPECT_THROW(rockParamsForPreset("huge"), Error);
    RockParams params;
    params.subdivisions = 0;
    EXPECT_THROW(makeRocks(1, 1, params), Error);
    params = RockParams{};
    params.minSize = 0.7f; // above maxSize
    EXPECT_THROW(makeRocks(1, 1, params), Error);
    params.minSize = std::nanf("");
    EXPECT_THROW(makeRocks(1, 1, params), Error);
    try {
        params = RockParams{};
        params.maxSize = -1.0f;
        makeRocks(1, 1, params);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("rocks: sizes"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace meadow
