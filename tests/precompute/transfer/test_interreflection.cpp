// Interreflection (Sloan, Kautz and Snyder 2002, section 4): the furnace bowl with its closed-form
// sum of bounces (docs/ARCHITECTURE.md, Light transfer), and the ground as a source of first-bounce
// light.
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace meadow::transfer {
namespace {

// The furnace: the inside of a hemispherical bowl of albedo rho (the lower half of a sphere,
// open at the top), under a uniform sky of radiance L = 1.
//
// On the inside of a sphere every surface element sees every area A of the sphere with the same
// form factor A / (4 pi R^2) (the sphere's classic radiosity property: the cosines at both ends
// and the distance cancel, cos * cos / (pi r^2) = 1 / (4 pi R^2)). So from any point of the bowl
//   - the opening (it lets through exactly what the missing upper half would show) has form
//     factor 1/2: direct irradiance E_0 = pi L / 2, the same everywhere;
//   - the bowl itself has form factor 1/2: a uniform radiosity B gives irradiance pi B / 2.
// Bounce k + 1 is then uniform as well: B_k = rho E_k / pi, E_(k+1) = pi B_k / 2 = (rho / 2) E_k,
// so E_k = (pi / 2) (rho / 2)^k and after N bounces E = (pi / 2) sum_(k=0..N) (rho / 2)^k.
// The bake's coefficient for a uniform sky is c00 = E / L_00 with L_00 = 2 sqrt(pi) (the
// projection of a constant 1), so the expected front c00 is (sqrt(pi) / 4) sum_(k=0..N) (rho / 2)^k.
double furnaceC00(double rho, uint32_t bounces) {
    double sum = 0.0;
    for (uint32_t k = 0; k <= bounces; ++k)
        sum += std::pow(rho / 2.0, double(k));
    return std::sqrt(std::numbers::pi) / 4.0 * sum;
}

TEST(Interreflection, FurnaceBowlMatchesTheAnalyticSumOfBounces) {
    // Three albedos at once, one per channel; 16 x 48 facets keep the chords' departure from the
    // sphere small (the form factors of the flat facets differ from the sphere's by < 0.5 %).
    // 4096 rays: the opening's sharp outline is the hardest case for the lattice (its error
    // there falls like N^-3/4; measured worst vertex 1.3 % at 4096 rays, 3 % at 1024).
    const glm::vec3 rho(0.9f, 0.6f, 0.3f);
    const test::OwnedMesh bowl = test::hemisphereBowl(1.0f, 16, 48, rho);
    const uint32_t rings = 16, segments = 48;
    // Every vertex but the rim's (its facets meet the opening edge-on): the bottom, the walls.
    const uint32_t probeCount = 1 + (rings - 1) * segments;

    for (uint32_t bounces : {0u, 1u, 3u}) {
        BakeSettings settings = test::isolatedSettings(4096);
        settings.bounces = bounces;
        const ClumpTransfer result = bakeTransfer(bowl.view(), settings);
        for (uint32_t v = 0; v < probeCount; ++v) {
            for (uint32_t c = 0; c < 3; ++c) {
                const double expected = furnaceC00(double(rho[int(c)]), bounces);
                // 2 %: the lattice error of 2048 rays per side (direct term and each gather) plus
                // the facets' departure from the sphere.
                EXPECT_NEAR(result.vertices.at(v, Side::Front, c)[0], expected, 0.02 * expected)
                    << "vertex " << v << " channel " << c << " after " << bounces << " bounces";
            }
        }
    }
}

TEST(Interreflection, EachBounceGathersOnlyThePreviousOne) {
    // In the furnace, bounce k alone is (rho / 2)^k of the direct term. A bake that gathered the
    // running total instead would add (rho / 2)(1 + rho / 2) at bounce 2 rather than (rho / 2)^2.
    const float rho = 0.8f;
    const test::OwnedMesh bowl = test::hemisphereBowl(1.0f, 12, 36, glm::vec3(rho));
    BakeSettings settings = test::isolatedSettings(1024);
    double previous = 0.0;
    std::vector<double> increments;
    for (uint32_t bounces = 0; bounces <= 2; ++bounces) {
        settings.bounces = bounces;
        const double c00 = bakeTransfer(bowl.view(), settings).vertices.at(0, Side::Front, 0)[0];
        increments.push_back(c00 - previous);
        previous = c00;
    }
    // Ratios of successive bounces: rho / 2 = 0.4 each; 0.02 covers the lattice error of 512 rays
    // per side (measured up to 0.011 at half that) and the coarser facets (the wrong rule would
    // give 0.56 at bounce 2).
    EXPECT_NEAR(increments[1] / increments[0], rho / 2.0, 0.02);
    EXPECT_NEAR(increments[2] / increments[1], rho / 2.0, 0.02);
}

TEST(Interreflection, GroundLightsAVertexFacingDown) {
    // A small sheet 0.5 m above an infinite ground, Front facing down: it sees only ground. The
    // ground model (transfer.h) without a grid: radiance groundAlbedo / pi * C(+y) . L everywhere,
    // so the front's irradiance transfer after one bounce is groundAlbedo * C(+y) per channel (a
    // uniform radiance over a hemisphere gives pi times it), and its direct term is zero.
    const test::OwnedMesh sheet = test::triangle({0.0f, 0.5f, 0.0f}, {0, -1, 0}, 0.01f);
    BakeSettings settings = test::isolatedSettings(1024);
    settings.groundPlane = true;
    settings.groundAlbedo = {0.3f, 0.6f, 0.9f};
    settings.bounces = 1;
    const ClumpTransfer result = bakeTransfer(sheet.view(), settings);
    const std::vector<double> up = test::clampedCosineOracle({0, 1, 0});
    for (uint32_t c = 0; c < 3; ++c) {
        const float* front = result.vertices.at(0, Side::Front, c);
        for (size_t i = 0; i < 9; ++i) {
            // 0.003: the lattice error of 512 rays per side on a whole hemisphere of a smooth
            // integrand (direct term's blocked sum, the gather's weights; measured <= 0.0004),
            // on values up to 0.9 * 1.02.
            EXPECT_NEAR(front[i], settings.groundAlbedo[int(c)] * up[i], 0.003)
                << "channel " << c << " coefficient " << i;
        }
    }
    // The back faces the open sky: unchanged by the ground (it sees none of it), exactly.
    test::expectSideNear(result.vertices, 0, Side::Back, up, 1e-5, "back facing the sky");

    // Without bounces the ground gives nothing.
    settings.bounces = 0;
    const ClumpTransfer direct = bakeTransfer(sheet.view(), settings);
    test::expectSideNear(direct.vertices, 0, Side::Front, std::vector<double>(9, 0.0), 0.003, "no bounce");
}

TEST(Interreflection, ShadowedGroundSendsLessLight) {
    // The ground lights the clump with its own shadowed transfer from the ground grid: a sheet
    // facing down 5 cm above the ground, under a 1 m roof 0.3 m up. The ground beneath the roof's
    // centre keeps only 1 - F = 0.23 of its sky (F = 0.77, the form factor of the roof; see
    // test_ground_transfer.cpp), and the sheet sees mostly that patch (half its cosine-weighted
    // view lies within 5 cm). Without a grid the ground model is the unoccluded cosine, and the
    // sheet gets groundAlbedo * C(+y), as in GroundLightsAVertexFacingDown.
    test::OwnedMesh mesh = test::triangle({0.0f, 0.05f, 0.0f}, {0, -1, 0}, 0.01f);
    mesh.append(test::horizontalQuad({0.0f, 0.3f, 0.0f}, 1.0f, false));
    BakeSettings settings = test::isolatedSettings(512);
    settings.groundPlane = true;
    settings.groundAlbedo = glm::vec3(0.5f);
    settings.bounces = 1;
    const double open = bakeTransfer(mesh.view(), settings).vertices.at(0, Side::Front, 0)[0];
    EXPECT_NEAR(open, 0.5 * test::clampedCosineOracle({0, 1, 0})[0], 0.01); // the lattice error, as above
    settings.groundGridSize = 2.0f;
    settings.groundGridResolution = 21; // 10 cm apart
    settings.groundRaysPerPoint = 256;
    const double shaded = bakeTransfer(mesh.view(), settings).vertices.at(0, Side::Front, 0)[0];
    // 0.23 at the centre, a little more towards the edge of the sheet's view (measured 0.246).
    EXPECT_LT(shaded, 0.32 * open);
    EXPECT_GT(shaded, 0.2 * open);
}

TEST(Interreflection, BouncedLightTakesTheColourOfWhatItHit) {
    // A grey sheet facing up 0.1 m under a 2 m red roof, no ground. The roof's underside sees
    // the lower sky, so its transfer is C(-y); it sends albedo / pi of it
    // down, and the sheet sees the roof under ~99 % of its cosine lobe (half-angle 84 degrees).
    // So the sheet's first bounce is ~albedo * C(-y) per channel: tinted by the roof, and a
    // response to light from BELOW (transfer is a function of the sky direction, and what
    // reaches the sheet first hit the roof from below).
    //
    // Which side of the roof is labelled Front must not matter: the sheet gathers the side that
    // faces it, the roof's underside, in both cases (a bake that took the Front regardless would
    // gather the roof's top, C(+y), and get the sign of the y coefficient wrong).
    for (bool roofFrontUp : {false, true}) {
        SCOPED_TRACE(roofFrontUp ? "roof Front facing up" : "roof Front facing down");
        test::OwnedMesh mesh = test::triangle({0.0f, 0.0f, 0.0f}, {0, 1, 0}, 0.02f);
        mesh.append(test::horizontalQuad({0.0f, 0.1f, 0.0f}, 2.0f, roofFrontUp, {0.9f, 0.1f, 0.1f}));
        BakeSettings settings = test::isolatedSettings(256);
        const ClumpTransfer direct = bakeTransfer(mesh.view(), settings);
        settings.bounces = 1;
        const ClumpTransfer bounced = bakeTransfer(mesh.view(), settings);
        double bounce[3][9];
        for (uint32_t c = 0; c < 3; ++c) {
            for (uint32_t i = 0; i < 9; ++i) {
                bounce[c][i] = double(bounced.vertices.at(0, Side::Front, c)[i]) -
                               double(direct.vertices.at(0, Side::Front, c)[i]);
            }
        }
        const std::vector<double> below = test::clampedCosineOracle({0, -1, 0});
        // 0.9 * 0.99 * 0.886 = 0.79 (measured 0.793 against 0.9 * 0.886 = 0.798); 0.02 covers the
        // 1 % of the lobe past the roof's edge and the lattice error of 128 rays per side.
        EXPECT_NEAR(bounce[0][0], 0.9 * below[0], 0.02);
        EXPECT_NEAR(bounce[0][sh::index(1, 0)], 0.9 * below[size_t(sh::index(1, 0))], 0.02); // < 0: from below
        // Same rays, same records, a uniform roof: the channels differ by the albedo ratio 9
        // exactly, up to float rounding.
        EXPECT_NEAR(bounce[0][0] / bounce[1][0], 9.0, 1e-4);
        EXPECT_NEAR(bounce[2][0], bounce[1][0], 1e-6);
    }
}

} // namespace
} // namespace meadow::transfer
