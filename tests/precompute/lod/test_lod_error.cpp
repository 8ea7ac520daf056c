// The LOD error report (precompute/lod/lod_error.cpp): analytic cases, then real clumps.
#include "lod_fixtures.h"

#include "core/error.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>

using namespace meadow;
using namespace meadow::test;

namespace {

// A 1 m x 0.2 m sheet folded into a tent: z = h (1 - |2x - 1|), the ridge along x = 0.5. Its
// "LOD" is the flat rectangle through its four corners (z = 0).
struct Tent {
    static constexpr float kHeight = 0.01f;
    TestMesh mesh = makeGrid(40, 4, 1.0f, 0.2f);
    std::vector<uint32_t> lodVertices{0, 40, 204, 164}; // counter-clockwise corners
    std::vector<uint32_t> lodIndices{0, 1, 2, 0, 2, 3};
    Tent() {
        for (glm::vec3& p : mesh.positions)
            p.z = kHeight * (1.0f - std::abs(2.0f * p.x - 1.0f));
    }
};

// Dense sampling for the analytic cases: a sample every ~2 mm.
LodErrorOptions dense() {
    LodErrorOptions options;
    options.samplesPerSquareMetre = 250000.0f;
    return options;
}

} // namespace

TEST(LodError, TentAgainstItsBaseMatchesTheAnalyticDistances) {
    const Tent tent;
    LodErrorInput in;
    in.positions = tent.mesh.positions;
    in.indices = tent.mesh.indices;
    const LodError e = measureLodError(in, tent.lodVertices, tent.lodIndices, dense());
    const double h = Tent::kHeight;
    // The nearest samples to the ridge lie within ~2 mm of it, where the tent is 0.4 % lower.
    EXPECT_LE(e.rest.hausdorff, h * 1.0001);
    EXPECT_GE(e.rest.hausdorff, h * 0.99);
    // Both ways the distance is the height (to within cos(atan 0.02) = 0.9998): its RMS over the
    // tent is h / sqrt(3) each way. 1 % covers the stratified sampling.
    EXPECT_NEAR(e.rest.rms, h / std::sqrt(3.0), 0.01 * h);
    EXPECT_EQ(e.deformed.hausdorff, 0.0); // no frames given
    EXPECT_EQ(e.motion.rms, 0.0);
    EXPECT_GT(e.fullSamples, 40000u);
}

TEST(LodError, LinearLightIsExactAndRigidMotionCostsNothing) {
    const Tent tent;
    std::vector<float> light(tent.mesh.positions.size());
    for (size_t v = 0; v < light.size(); ++v)
        light[v] = 2.0f * tent.mesh.positions[v].x + 0.5f;
    std::vector<std::vector<glm::vec3>> frames(1, tent.mesh.positions);
    for (glm::vec3& p : frames[0])
        p += glm::vec3(0.1f, 0.2f, 0.3f);
    LodErrorInput in;
    in.positions = tent.mesh.positions;
    in.indices = tent.mesh.indices;
    in.lightScalar = light;
    in.frames = frames;
    const LodError e = measureLodError(in, tent.lodVertices, tent.lodIndices, dense());
    // A scalar linear in x is interpolated exactly by the flat LOD. From the tent to the LOD the
    // nearest point keeps x; from the LOD to the tent it slides along the slanted face by at most
    // h x slope = 2 h^2, which changes the scalar by 2 x 2 h^2 = 4e-4 (plus float rounding).
    const double h = Tent::kHeight;
    EXPECT_LT(e.light.hausdorff, 4.0 * h * h + 1e-5);
    EXPECT_GT(e.light.hausdorff, 2.0 * h * h); // that slide does happen: the test sees it
    // A translation moves every point alike: float rounding of 0.3 m displacements.
    EXPECT_LT(e.motion.hausdorff, 1e-5);
    // ... and leaves the distances as they were (rounding of positions moved by up to 0.3 m).
    EXPECT_NEAR(e.deformed.hausdorff, e.rest.hausdorff, 1e-6);
    EXPECT_NEAR(e.deformed.rms, e.rest.rms, 1e-6);
}

TEST(LodError, DeformationThatTheLodCannotFollowShowsInMotionAndDeformedErrors) {
    const Tent tent;
    std::vector<std::vector<glm::vec3>> frames(1, tent.mesh.positions);
    for (glm::vec3& p : frames[0])
        p.z *= 2.0f; // the ridge rises to 2h; the LOD's corners (z = 0) do not move
    LodErrorInput in;
    in.positions = tent.mesh.positions;
    in.indices = tent.mesh.indices;
    in.frames = frames;
    const LodError e = measureLodError(in, tent.lodVertices, tent.lodIndices, dense());
    const double h = Tent::kHeight;
    // Deformed: the tent of height 2h against the flat LOD. Motion: displacement z (up to h) at
    // the full surface against none on the LOD. Same sampling tolerances as above.
    EXPECT_NEAR(e.deformed.hausdorff, 2.0 * h, 0.01 * 2.0 * h);
    EXPECT_NEAR(e.deformed.rms, 2.0 * h / std::sqrt(3.0), 0.01 * 2.0 * h);
    EXPECT_NEAR(e.motion.hausdorff, h, 0.01 * h);
    EXPECT_NEAR(e.motion.rms, h / std::sqrt(3.0), 0.01 * h);
}

TEST(LodError, FullMeshAgainstItselfIsExact) {
    const IrisCase& iris = irisCase("ci");
    std::vector<uint32_t> all(iris.clump.mesh.vertexCount());
    for (uint32_t v = 0; v < all.size(); ++v)
        all[v] = v;
    const LodError e = measureLodError(iris.errorInput(), all, iris.clump.mesh.indices);
    // Every sample lies on the other surface; float rounding of a nearest-point query at ~1 m.
    EXPECT_LT(e.rest.hausdorff, 1e-6);
    EXPECT_LT(e.deformed.hausdorff, 1e-6);
    EXPECT_LT(e.light.hausdorff, 1e-5);
    EXPECT_LT(e.motion.hausdorff, 1e-5);
}

TEST(LodError, ErrorsGrowWithTheLodIndexOnARealClump) {
    for (const char* preset : {"ci", "full"}) {
        const IrisCase& iris = irisCase(preset);
        const std::array<MeshLod, kLodCount> lods = buildLods(iris.input());
        const std::array<LodError, kLodCount> e = measureLodErrors(iris.errorInput(), lods);
        for (uint32_t i = 0; i < kLodCount; ++i) {
            std::printf("[ lod %s ] LOD %u: %5u tris %5zu verts | rest H %.4f RMS %.5f | deformed H %.4f RMS %.5f | "
                        "light H %.4f RMS %.5f | motion H %.4f RMS %.5f m\n",
                        preset, i, lods[i].triangleCount(), lods[i].vertices.size(), e[i].rest.hausdorff, e[i].rest.rms,
                        e[i].deformed.hausdorff, e[i].deformed.rms, e[i].light.hausdorff, e[i].light.rms,
                        e[i].motion.hausdorff, e[i].motion.rms);
        }
        // Nested LODs from one collapse sequence lose more at every step. Non-decreasing exactly:
        // a coarser LOD is a strict simplification of the finer one, and with ~20,000 samples the
        // sampled figures cannot fluctuate by the margin between LODs (3-4x fewer triangles each).
        for (uint32_t i = 1; i < kLodCount; ++i) {
            SCOPED_TRACE(std::string(preset) + " LOD " + std::to_string(i));
            EXPECT_GE(e[i].rest.hausdorff, e[i - 1].rest.hausdorff);
            EXPECT_GE(e[i].rest.rms, e[i - 1].rest.rms);
            EXPECT_GE(e[i].deformed.hausdorff, e[i - 1].deformed.hausdorff);
            EXPECT_GE(e[i].deformed.rms, e[i - 1].deformed.rms);
            EXPECT_GE(e[i].light.rms, e[i - 1].light.rms);
            EXPECT_GE(e[i].motion.rms, e[i - 1].motion.rms);
        }
        // LOD 0 is the full mesh: zero to rounding (see FullMeshAgainstItselfIsExact).
        EXPECT_LT(e[0].rest.hausdorff, 1e-6);
        EXPECT_LT(e[0].motion.hausdorff, 1e-5);
    }
}

TEST(LodError, SameBytesForAnyThreadCount) {
    const IrisCase& iris = irisCase("ci");
    const SimplifiedMesh lod = simplifyMesh(iris.input(), uint32_t(iris.clump.mesh.triangleCount() / 10));
    LodError one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = measureLodError(iris.errorInput(), lod.keptVertices, lod.indices);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = measureLodError(iris.errorInput(), lod.keptVertices, lod.indices);
    }
    EXPECT_EQ(std::memcmp(&one, &two, sizeof(LodError)), 0);
    EXPECT_GT(one.rest.hausdorff, 0.0);
}

TEST(LodError, RejectsBadInput) {
    const Tent tent;
    std::vector<float> light(tent.mesh.positions.size(), 1.0f);
    std::vector<std::vector<glm::vec3>> frames(2, tent.mesh.positions);
    auto expectError = [&](auto&& edit, const std::string& needle) {
        LodErrorInput in;
        in.positions = tent.mesh.positions;
        in.indices = tent.mesh.indices;
        std::vector<uint32_t> vertices = tent.lodVertices, indices = tent.lodIndices;
        std::vector<float> lightCopy = light;
        std::vector<std::vector<glm::vec3>> framesCopy = frames;
        LodErrorOptions options;
        edit(in, vertices, indices, lightCopy, framesCopy, options);
        try {
            measureLodError(in, vertices, indices, options);
            ADD_FAILURE() << "no error; expected: " << needle;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "message: " << e.what();
        }
    };
    expectError([](auto&, auto&, auto& i, auto&, auto&, auto&) { i[5] = 4; },
                "LOD error: LOD index 5 is 4, the LOD has 4 vertices");
    expectError([](auto&, auto& v, auto&, auto&, auto&, auto&) { v[1] = 999; },
                "LOD vertex 1 is original vertex 999, the full mesh has 205");
    expectError([](auto&, auto&, auto& i, auto&, auto&, auto&) { i.clear(); },
                "the LOD needs a whole, non-zero number");
    expectError(
        [](LodErrorInput& in, auto&, auto&, std::vector<float>& l, auto&, auto&) {
            l.pop_back();
            in.lightScalar = l;
        },
        "204 light values for 205 vertices");
    expectError(
        [](LodErrorInput& in, auto&, auto&, auto&, std::vector<std::vector<glm::vec3>>& f, auto&) {
            f[1].resize(10);
            in.frames = f;
        },
        "frame 1 has 10 positions for 205 vertices");
    expectError(
        [](LodErrorInput& in, auto&, auto&, auto&, std::vector<std::vector<glm::vec3>>& f, auto&) {
            f[0][7].x = std::nanf("");
            in.frames = f;
        },
        "frame 0 holds a position that is not finite");
    expectError([](auto&, auto&, auto&, auto&, auto&, LodErrorOptions& o) { o.samplesPerSquareMetre = 0.0f; },
                "samplesPerSquareMetre must be finite and > 0");
}
