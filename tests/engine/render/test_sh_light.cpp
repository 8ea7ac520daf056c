// The sky carried into a placed clump's frame (shaders/shared/sh_light.h), checked against
// precompute/light/sh.h: its general rotation for turned instances, exact quadrature of the
// transformed function for mirrored ones, and where a bright lobe ends up.
//
// A (the clump -> world map without translation) is built here from matrices, R(yaw) M, not from
// the azimuth formulas the header uses, so the tests check those formulas too.
#include "sh_light.h"

#include "core/random.h"
#include "light/sh.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace meadow {
namespace {

constexpr int kOrder = 3;
constexpr size_t kCount = 9;

// The turn about +y of field placement: x' = cos(yaw) x + sin(yaw) z, z' = -sin(yaw) x + cos(yaw) z.
glm::dmat3 yawMatrix(double yaw) {
    const double c = std::cos(yaw), s = std::sin(yaw);
    // glm is column-major: columns are the images of x, y, z.
    return glm::dmat3(glm::dvec3(c, 0.0, -s), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(s, 0.0, c));
}

// The reflection about the vertical plane containing the wind direction (wx, 0, wz).
glm::dmat3 mirrorMatrix(double wx, double wz) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(wz, 0.0, -wx)); // horizontal, normal to the wind
    return glm::dmat3(1.0) - 2.0 * glm::outerProduct(n, n);
}

// A = R(yaw) M (M only when mirrored): clump directions -> world directions.
glm::dmat3 clumpToWorld(double yaw, bool mirrored, double wx, double wz) {
    return mirrored ? yawMatrix(yaw) * mirrorMatrix(wx, wz) : yawMatrix(yaw);
}

std::vector<glm::dvec3> randomRgb(Random& random) {
    std::vector<glm::dvec3> c(kCount);
    for (glm::dvec3& v : c)
        v = glm::dvec3(random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f));
    return c;
}

// The header's view of the same coefficients: floats, sh[3 i + c].
std::array<float, 27> toFloats(const std::vector<glm::dvec3>& c) {
    std::array<float, 27> out{};
    for (size_t i = 0; i < kCount; ++i)
        for (int k = 0; k < 3; ++k)
            out[3 * i + size_t(k)] = float(c[i][k]);
    return out;
}

std::vector<glm::dvec3> fromFloats(const float (&sh)[27]) {
    std::vector<glm::dvec3> out(kCount);
    for (size_t i = 0; i < kCount; ++i)
        out[i] = glm::dvec3(sh[3 * i], sh[3 * i + 1], sh[3 * i + 2]);
    return out;
}

// The header's transform of world coefficients c for one instance.
std::vector<glm::dvec3> toClumpFrame(const std::vector<glm::dvec3>& c, double yaw, bool mirrored, double wx,
                                     double wz) {
    const std::array<float, 27> in = toFloats(c);
    float skyIn[27];
    for (size_t k = 0; k < 27; ++k)
        skyIn[k] = in[k];
    float skyOut[27];
    const float windAzimuth = float(std::atan2(wx, wz));
    gpu::shSkyToClumpFrame(skyIn, gpu::shClumpFrameSign(mirrored),
                           gpu::shClumpFrameDelta(float(yaw), mirrored, windAzimuth), skyOut);
    return fromFloats(skyOut);
}

// Coefficients of g(ω) = f(A ω) by quadrature: g is band-limited to order 3 like f, so 4 Gauss
// nodes and 7 azimuths integrate g Y exactly; more are used to leave no doubt.
std::vector<glm::dvec3> projectTransformed(const std::vector<glm::dvec3>& c, const glm::dmat3& a) {
    return sh::projectQuadratureRgb(
        kOrder, [&](const glm::dvec3& w) { return sh::reconstructRgb(kOrder, c, a * w); }, 8, 16);
}

const double kYaws[] = {0.0, 0.3, -1.2, 1.5707963267948966, 2.9, 3.14159265358979, -2.4, 5.5, 11.0};
const glm::dvec2 kWinds[] = {{0.0, 1.0}, {1.0, 0.0}, {0.6, -0.8}, {-0.3, -0.4}, {-2.0, 0.5}};

TEST(ShLight, Constants) {
    EXPECT_EQ(gpu::kShLightOrder, uint32_t(sh::kDefaultOrder));
    EXPECT_EQ(gpu::kShLightCoefficients, uint32_t(sh::coefficientCount(kOrder)));
    EXPECT_EQ(gpu::kShLightRgbFloats, 3u * gpu::kShLightCoefficients);
    EXPECT_EQ(gpu::shClumpFrameSign(false), 1.0f);
    EXPECT_EQ(gpu::shClumpFrameSign(true), -1.0f);
    EXPECT_EQ(gpu::shClumpFrameDelta(0.7f, false, 2.0f), 0.7f);
    EXPECT_FLOAT_EQ(gpu::shClumpFrameDelta(0.7f, true, 2.0f), 4.7f);
}

TEST(ShLight, TurnedInstanceMatchesGeneralRotation) {
    // rotateRgb(c, R) gives the coefficients of f(Rᵀ ω); the clump frame needs f(A ω), so R = Aᵀ.
    Random random(17);
    for (int trial = 0; trial < 8; ++trial) {
        const std::vector<glm::dvec3> c = randomRgb(random);
        for (double yaw : kYaws) {
            const glm::dmat3 a = clumpToWorld(yaw, false, 0.0, 1.0);
            const std::vector<glm::dvec3> expected = sh::rotateRgb(kOrder, c, glm::transpose(a));
            const std::vector<glm::dvec3> got = toClumpFrame(c, yaw, false, 0.0, 1.0);
            for (size_t i = 0; i < kCount; ++i)
                for (int k = 0; k < 3; ++k)
                    // Tolerance: float inputs and arithmetic on values of size ~1 (~1e-7 each).
                    EXPECT_NEAR(got[i][k], expected[i][k], 1e-5)
                        << "trial " << trial << " yaw " << yaw << " i " << i << " channel " << k;
        }
    }
}

TEST(ShLight, MirroredInstanceMatchesProjectionOfTheTransformedSky) {
    Random random(23);
    for (int trial = 0; trial < 4; ++trial) {
        const std::vector<glm::dvec3> c = randomRgb(random);
        for (const glm::dvec2& wind : kWinds)
            for (double yaw : kYaws)
                for (bool mirrored : {false, true}) {
                    const glm::dmat3 a = clumpToWorld(yaw, mirrored, wind.x, wind.y);
                    const std::vector<glm::dvec3> expected = projectTransformed(c, a);
                    const std::vector<glm::dvec3> got = toClumpFrame(c, yaw, mirrored, wind.x, wind.y);
                    for (size_t i = 0; i < kCount; ++i)
                        for (int k = 0; k < 3; ++k)
                            // Tolerance: exact quadrature; float rounding of the header's inputs,
                            // angles (up to ~15 rad) and products remains.
                            EXPECT_NEAR(got[i][k], expected[i][k], 1e-4)
                                << "trial " << trial << " wind " << wind.x << "," << wind.y << " yaw " << yaw
                                << " mirrored " << mirrored << " i " << i << " channel " << k;
                }
    }
}

TEST(ShLight, InPlaceTransformEqualsSeparateOutput) {
    Random random(5);
    const std::vector<glm::dvec3> c = randomRgb(random);
    const std::array<float, 27> values = toFloats(c);
    float in[27], out[27], inPlace[27];
    for (size_t k = 0; k < 27; ++k)
        in[k] = inPlace[k] = values[k];
    gpu::shSkyToClumpFrame(in, -1.0f, 0.9f, out);
    gpu::shSkyToClumpFrame(inPlace, -1.0f, 0.9f, inPlace);
    for (size_t k = 0; k < 27; ++k)
        EXPECT_EQ(inPlace[k], out[k]) << k;
}

// The unit direction at polar angle theta from +y and azimuth phi from +z towards +x.
glm::dvec3 direction(double theta, double phi) {
    return glm::dvec3(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
}

// The direction where the band-limited function c is largest (channel `k`): a 1-degree grid
// search, then a finer search around the best cell.
glm::dvec3 peak(const std::vector<glm::dvec3>& c, int k) {
    const double degree = 3.14159265358979323846 / 180.0;
    double bestTheta = 0.0, bestPhi = 0.0, best = -1e300;
    auto visit = [&](double theta, double phi) {
        const double v = sh::reconstructRgb(kOrder, c, direction(theta, phi))[k];
        if (v > best) {
            best = v;
            bestTheta = theta;
            bestPhi = phi;
        }
    };
    for (int i = 0; i <= 180; ++i)
        for (int j = 0; j < 360; ++j)
            visit(i * degree, j * degree);
    const double theta0 = bestTheta, phi0 = bestPhi;
    for (int i = -50; i <= 50; ++i)
        for (int j = -50; j <= 50; ++j)
            visit(theta0 + i * 0.02 * degree, phi0 + j * 0.02 * degree);
    return direction(bestTheta, bestPhi);
}

TEST(ShLight, BrightLobeSitsWhereTheClumpSeesIt) {
    // A sky of a faint uniform ambient plus a warm clamped-cosine lobe about dWorld. In the clump
    // frame the lobe must sit at A⁻¹ dWorld: the direction the clump sees the light from.
    const std::vector<double> lobe = sh::clampedCosineZonal(kOrder);
    const glm::dvec3 warm(3.0, 2.0, 1.0);
    const glm::dvec3 dWorlds[] = {glm::normalize(glm::dvec3(0.8, 0.5, 0.1)),
                                  glm::normalize(glm::dvec3(-0.2, 0.3, -0.9)),
                                  glm::normalize(glm::dvec3(0.4, -0.2, 0.7))};
    for (const glm::dvec3& dWorld : dWorlds)
        for (const glm::dvec2& wind : {kWinds[2], kWinds[4]})
            for (double yaw : {0.0, 0.3, 2.9, -2.4})
                for (bool mirrored : {false, true}) {
                    const std::vector<double> turned = sh::rotateZonal(kOrder, lobe, dWorld);
                    std::vector<glm::dvec3> sky(kCount);
                    for (size_t i = 0; i < kCount; ++i)
                        sky[i] = warm * turned[i];
                    sky[0] += glm::dvec3(0.1); // ambient

                    const glm::dmat3 a = clumpToWorld(yaw, mirrored, wind.x, wind.y);
                    const glm::dvec3 expected = glm::transpose(a) * dWorld; // A is orthogonal
                    const std::vector<glm::dvec3> clumpSky = toClumpFrame(sky, yaw, mirrored, wind.x, wind.y);
                    for (int k = 0; k < 3; ++k) {
                        const glm::dvec3 found = peak(clumpSky, k);
                        // Tolerance: the fine search steps 0.02 degrees; float coefficients move
                        // the flat-topped maximum by far less than 0.1 degree (cos = 1 - 1.5e-6).
                        EXPECT_GT(glm::dot(found, expected), std::cos(0.1 * 3.14159265358979323846 / 180.0))
                            << "yaw " << yaw << " mirrored " << mirrored << " channel " << k;
                    }
                    // A zonal lobe is symmetric about its axis, so even under the mirror its
                    // coefficients in the clump frame are exactly those of the lobe about A⁻¹ dWorld.
                    const std::vector<double> moved = sh::rotateZonal(kOrder, lobe, expected);
                    for (size_t i = 0; i < kCount; ++i)
                        for (int k = 0; k < 3; ++k)
                            EXPECT_NEAR(clumpSky[i][k], warm[k] * moved[i] + (i == 0 ? 0.1 : 0.0), 1e-5)
                                << "yaw " << yaw << " mirrored " << mirrored << " i " << i;
                }
}

} // namespace
} // namespace meadow
