// The SH module against the oracles of docs/ARCHITECTURE.md, Light transfer: projection
// (quadrature, Monte Carlo, lat-long images), zonal harmonics, convolution and irradiance.
#include "core/random.h"
#include "light/latlong.h"
#include "light/sh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace meadow {
namespace {

const double kTwoSqrtPi = 2.0 * std::sqrt(M_PI); // 3.5449077

glm::dvec3 randomUnit(Random& random) {
    for (;;) {
        const glm::dvec3 v(random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f));
        const double length = glm::length(v);
        if (length > 0.1 && length <= 1.0)
            return v / length;
    }
}

// An orthonormal frame whose second column (the local "up") is `axis`.
glm::dmat3 frameAround(const glm::dvec3& axis) {
    const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
    const glm::dvec3 tangent = glm::normalize(glm::cross(axis, helper));
    const glm::dvec3 bitangent = glm::cross(tangent, axis);
    return glm::dmat3(bitangent, axis, tangent); // columns: x, y, z with det +1
}

TEST(ShProjection, ConstantProjectsToTwoSqrtPi) {
    const auto one = [](const glm::dvec3&) { return 1.0; };
    for (int order = 1; order <= sh::kMaxOrder; ++order) {
        const std::vector<double> c = sh::projectQuadrature(order, one, order + 1, 2 * order + 1);
        // Tolerance: the quadrature is exact for a constant times the basis; what remains is the
        // rounding of a few hundred terms.
        EXPECT_NEAR(c[0], kTwoSqrtPi, 1e-12) << "order " << order;
        for (size_t i = 1; i < c.size(); ++i)
            EXPECT_NEAR(c[i], 0.0, 1e-12) << "order " << order << " coefficient " << i;
    }
    // Monte Carlo: every sample gives 4 pi Y00 = 2 sqrt(pi) exactly, so c00 has zero variance.
    const sh::MonteCarloProjection mc = sh::projectMonteCarlo(3, one, 16, 7);
    EXPECT_NEAR(mc.coefficients[0], kTwoSqrtPi, 1e-12);
    EXPECT_NEAR(mc.standardError[0], 0.0, 1e-6); // rounding of the variance of identical terms
}

TEST(ShProjection, QuadratureWeightsCoverTheSphereAndBands) {
    // Tolerance: sums of a few thousand positive weights in double precision.
    double total = 0.0;
    for (const sh::SphereSample& s : sh::quadratureSamples(12, 24))
        total += s.weight;
    EXPECT_NEAR(total, 4.0 * M_PI, 1e-12);
    double upper = 0.0;
    for (const sh::SphereSample& s : sh::quadratureSamples(5, 9, 0.0, 1.0)) {
        upper += s.weight;
        EXPECT_GT(s.direction.y, 0.0);
        EXPECT_NEAR(glm::length(s.direction), 1.0, 1e-14);
    }
    EXPECT_NEAR(upper, 2.0 * M_PI, 1e-12);
    double stratified = 0.0;
    for (const sh::SphereSample& s : sh::stratifiedSamples(10, 3))
        stratified += s.weight;
    EXPECT_NEAR(stratified, 4.0 * M_PI, 1e-12);
}

TEST(ShZonal, ClampedCosineAboutUpProjectsToTheOracle) {
    // max(cos theta, 0) is the polynomial y on the upper hemisphere and 0 below; integrating the
    // upper band alone keeps the Gauss rule exact (the kink at the horizon is its boundary).
    const int order = sh::kMaxOrder;
    const std::vector<sh::SphereSample> upper = sh::quadratureSamples(order + 1, 2 * order + 1, 0.0, 1.0);
    const std::vector<double> projected = sh::project(order, upper, [](const glm::dvec3& d) { return d.y; });
    const std::vector<double> zonal = sh::clampedCosineZonal(order);
    // Tolerance: the oracle values are given to 6 decimals (docs/ARCHITECTURE.md, Light transfer).
    EXPECT_NEAR(projected[size_t(sh::index(0, 0))], 0.886227, 1e-6);
    EXPECT_NEAR(projected[size_t(sh::index(1, 0))], 1.023327, 1e-6);
    EXPECT_NEAR(projected[size_t(sh::index(2, 0))], 0.495416, 1e-6);
    EXPECT_NEAR(zonal[0], 0.886227, 1e-6);
    EXPECT_NEAR(zonal[1], 1.023327, 1e-6);
    EXPECT_NEAR(zonal[2], 0.495416, 1e-6);
    for (int l = 0; l < order; ++l)
        for (int m = -l; m <= l; ++m) {
            const double expected = m == 0 ? zonal[size_t(l)] : 0.0;
            // Tolerance: exact quadrature against a closed form, both in double precision.
            EXPECT_NEAR(projected[size_t(sh::index(l, m))], expected, 1e-12) << "l " << l << " m " << m;
        }
    // The convolution weights pi, 2 pi / 3, pi / 4 (Ramamoorthi and Hanrahan, eq. 8).
    const std::vector<double> ones(size_t(sh::coefficientCount(3)), 1.0);
    const std::vector<double> e = sh::irradiance(3, ones);
    EXPECT_NEAR(e[0], M_PI, 1e-12);
    EXPECT_NEAR(e[2], 2.0 * M_PI / 3.0, 1e-12);
    EXPECT_NEAR(e[6], M_PI / 4.0, 1e-12);
}

TEST(ShZonal, RotatedClampedCosineProjectsLikeTheTurnedFunction) {
    Random random(11);
    const int order = 5;
    const std::vector<double> zonal = sh::clampedCosineZonal(order);
    for (int trial = 0; trial < 4; ++trial) {
        const glm::dvec3 axis = randomUnit(random);
        const std::vector<double> turned = sh::rotateZonal(order, zonal, axis);
        // The hemisphere about `axis`, integrated exactly with a rotated band rule.
        const glm::dmat3 frame = frameAround(axis);
        std::vector<sh::SphereSample> samples = sh::quadratureSamples(order + 1, 2 * order + 1, 0.0, 1.0);
        for (sh::SphereSample& s : samples)
            s.direction = frame * s.direction;
        const std::vector<double> projected =
            sh::project(order, samples, [&](const glm::dvec3& d) { return glm::dot(d, axis); });
        for (size_t i = 0; i < projected.size(); ++i)
            EXPECT_NEAR(turned[i], projected[i], 1e-12) << "trial " << trial << " coefficient " << i;
    }
}

TEST(ShIrradiance, UnitDirectionalLightMatchesTheClosedForm) {
    // docs/ARCHITECTURE.md, Light transfer: E(x) = 3/32 + x/2 + 15 x^2 / 32, x the cosine between
    // normal and light.
    Random random(5);
    for (int trial = 0; trial < 8; ++trial) {
        const glm::dvec3 light = randomUnit(random);
        const std::vector<double> e = sh::irradiance(3, sh::directionalLight(3, light));
        // Tolerance: closed form against three bands of double arithmetic.
        EXPECT_NEAR(sh::reconstruct(3, e, light), 1.0625, 1e-12);
        EXPECT_NEAR(sh::reconstruct(3, e, -light), 0.0625, 1e-12);
        for (int k = 0; k < 8; ++k) {
            const glm::dvec3 normal = randomUnit(random);
            const double x = glm::dot(normal, light);
            EXPECT_NEAR(sh::reconstruct(3, e, normal), 3.0 / 32.0 + x / 2.0 + 15.0 * x * x / 32.0, 1e-12);
        }
    }
}

TEST(ShIrradiance, BandLimitedRadianceMatchesDirectIntegration) {
    // For radiance of order 3 the convolution is exact: E(n) holds only bands 0-2 too. The direct
    // integral ∫ L(ω) max(n · ω, 0) dω uses a band rule over the hemisphere about n, which is exact
    // for the polynomial integrand there.
    Random random(17);
    const int order = 3;
    std::vector<glm::dvec3> radiance(size_t(sh::coefficientCount(order)));
    for (glm::dvec3& c : radiance)
        c = glm::dvec3(random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f));
    radiance[0] += glm::dvec3(4.0); // mostly positive, like light
    const std::vector<glm::dvec3> e = sh::irradianceRgb(order, radiance);
    const std::vector<sh::SphereSample> hemisphere = sh::quadratureSamples(8, 16, 0.0, 1.0);
    for (int trial = 0; trial < 6; ++trial) {
        const glm::dvec3 normal = randomUnit(random);
        const glm::dmat3 frame = frameAround(normal);
        glm::dvec3 direct(0.0);
        for (const sh::SphereSample& s : hemisphere) {
            const glm::dvec3 d = frame * s.direction;
            direct += sh::reconstructRgb(order, radiance, d) * glm::dot(d, normal) * s.weight;
        }
        const glm::dvec3 fromSh = sh::reconstructRgb(order, e, normal);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(fromSh[c], direct[c], 1e-11) << "trial " << trial; // exact rules, rounding only
    }
}

TEST(ShZonal, ConvolutionScalesEachBand) {
    const int order = 4;
    std::vector<double> c(size_t(sh::coefficientCount(order)));
    for (size_t i = 0; i < c.size(); ++i)
        c[i] = 1.0 + double(i);
    const std::vector<double> kernel = {2.0, -1.0, 0.5, 0.0};
    const std::vector<double> out = sh::convolveZonal(order, c, kernel);
    for (int l = 0; l < order; ++l)
        for (int m = -l; m <= l; ++m) {
            const size_t i = size_t(sh::index(l, m));
            EXPECT_NEAR(out[i], c[i] * std::sqrt(4.0 * M_PI / (2 * l + 1)) * kernel[size_t(l)], 1e-12);
        }
}

// exp(2 a · ω) + a cubic: smooth, with energy in every band, so no coefficient is trivially zero.
double smoothTestFunction(const glm::dvec3& d) {
    const glm::dvec3 a = glm::normalize(glm::dvec3(0.3, 0.7, -0.2));
    return std::exp(2.0 * glm::dot(a, d)) + 0.5 * d.x * d.y * d.z + 0.25 * d.z;
}

TEST(ShProjection, MonteCarloAndQuadratureAgreeWithinTheirErrors) {
    for (int order : {3, sh::kMaxOrder}) {
        // Quadrature error: the function is entire, so doubling the nodes should change nothing
        // beyond rounding; that difference is the stated error of the reference.
        const std::vector<double> coarse = sh::projectQuadrature(order, smoothTestFunction, 24, 48);
        const std::vector<double> fine = sh::projectQuadrature(order, smoothTestFunction, 48, 96);
        for (size_t i = 0; i < fine.size(); ++i)
            ASSERT_NEAR(coarse[i], fine[i], 1e-12) << "order " << order << " coefficient " << i;

        const sh::MonteCarloProjection mc = sh::projectMonteCarlo(order, smoothTestFunction, 48, 2024);
        double worstRatio = 0.0;
        for (size_t i = 0; i < fine.size(); ++i) {
            ASSERT_GT(mc.standardError[i], 0.0);
            // Tolerance: 4 standard errors (a 1-in-15,000 event for one Gaussian coefficient, and
            // the error bound is conservative for stratified samples).
            EXPECT_NEAR(mc.coefficients[i], fine[i], 4.0 * mc.standardError[i]) << "order " << order << " i " << i;
            worstRatio = std::max(worstRatio, std::abs(mc.coefficients[i] - fine[i]) / mc.standardError[i]);
        }
        // The standard error is meaningful: with 4,608 samples it is a few percent of c00.
        EXPECT_LT(mc.standardError[0], 0.05 * fine[0]);
        // Stratification pays: the actual errors sit well inside the plain Monte Carlo bound.
        EXPECT_LT(worstRatio, 2.0) << "order " << order;
    }
}

TEST(ShProjection, MonteCarloIsDeterministicPerSeed) {
    const auto a = sh::projectMonteCarlo(3, smoothTestFunction, 8, 99);
    const auto b = sh::projectMonteCarlo(3, smoothTestFunction, 8, 99);
    const auto c = sh::projectMonteCarlo(3, smoothTestFunction, 8, 100);
    EXPECT_EQ(a.coefficients, b.coefficients);
    EXPECT_NE(a.coefficients, c.coefficients);
}

TEST(ShProjection, RgbProjectionIsPerChannel) {
    const auto f = [](const glm::dvec3& d) { return glm::dvec3(1.0, d.y, smoothTestFunction(d)); };
    const std::vector<glm::dvec3> rgb = sh::projectQuadratureRgb(4, f, 24, 48);
    const std::vector<double> blue = sh::projectQuadrature(4, smoothTestFunction, 24, 48);
    EXPECT_NEAR(rgb[0].r, kTwoSqrtPi, 1e-12);
    EXPECT_NEAR(rgb[2].g, std::sqrt(4.0 * M_PI / 3.0), 1e-12); // y = sqrt(4 pi / 3) Y10
    for (size_t i = 0; i < blue.size(); ++i)
        EXPECT_EQ(rgb[i].b, blue[i]); // the same arithmetic, channel by channel
}

TEST(LatLong, MappingFollowsTheDocumentedAxes) {
    // Tolerance: double trigonometry at exact fractions of pi.
    const auto near = [](const glm::dvec3& a, const glm::dvec3& b) { return glm::length(a - b) < 1e-12; };
    EXPECT_TRUE(near(latLongDirection(0.3, 0.0), {0, 1, 0}));   // row 0: zenith
    EXPECT_TRUE(near(latLongDirection(0.0, 0.5), {0, 0, 1}));   // column 0 at the horizon: north
    EXPECT_TRUE(near(latLongDirection(0.25, 0.5), {1, 0, 0}));  // a quarter across: east
    EXPECT_TRUE(near(latLongDirection(0.5, 0.5), {0, 0, -1}));  // centre: south
    EXPECT_TRUE(near(latLongDirection(0.75, 0.5), {-1, 0, 0})); // three quarters: west
    EXPECT_TRUE(near(latLongDirection(0.6, 1.0), {0, -1, 0}));  // last row: nadir
    Random random(3);
    for (int k = 0; k < 100; ++k) {
        const glm::dvec3 d = randomUnit(random);
        const glm::dvec2 uv = latLongCoordinates(d);
        EXPECT_TRUE(uv.x >= 0.0 && uv.x < 1.0 && uv.y >= 0.0 && uv.y <= 1.0);
        EXPECT_TRUE(near(latLongDirection(uv.x, uv.y), d));
    }
    double total = 0.0;
    for (uint32_t j = 0; j < 7; ++j)
        total += 13 * latLongPixelSolidAngle(j, 13, 7);
    EXPECT_NEAR(total, 4.0 * M_PI, 1e-12);
}

TEST(LatLong, ConstantImageProjectsToTwoSqrtPi) {
    for (auto [w, h] : {std::pair<uint32_t, uint32_t>{64, 32}, {5, 3}, {2, 1}}) {
        const std::vector<float> image(size_t(w) * h * 3, 1.0f);
        const std::vector<glm::dvec3> c = sh::projectLatLong(3, w, h, image);
        // Tolerance: the pixel solid angles are exact and the 2 x 2 rule integrates bands 0-2
        // exactly over each pixel; rounding of a few thousand terms remains.
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_NEAR(c[0][ch], kTwoSqrtPi, 1e-12) << w << "x" << h;
            // A 2 x 1 image has 4 azimuth points in all and cannot tell cos(2 phi) from a
            // constant; only its c00 (exact solid angles) is checked.
            for (size_t i = 1; w > 2 && i < c.size(); ++i)
                EXPECT_NEAR(c[i][ch], 0.0, 1e-12) << w << "x" << h << " coefficient " << i;
        }
    }
}

TEST(LatLong, ImageOfABandLimitedFunctionProjectsBackToIt) {
    // An image sampled at pixel centres from known coefficients projects back to them up to the
    // midpoint-sampling error of the image itself, O(pixel^2): about 1e-4 at 256 x 128.
    Random random(8);
    const int order = 4;
    std::vector<glm::dvec3> truth(size_t(sh::coefficientCount(order)));
    for (glm::dvec3& c : truth)
        c = glm::dvec3(random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f));
    const uint32_t w = 256, h = 128;
    std::vector<float> image(size_t(w) * h * 3);
    for (uint32_t j = 0; j < h; ++j)
        for (uint32_t i = 0; i < w; ++i) {
            const glm::dvec3 v = sh::reconstructRgb(order, truth, latLongDirection((i + 0.5) / w, (j + 0.5) / h));
            for (int ch = 0; ch < 3; ++ch)
                image[(size_t(j) * w + i) * 3 + size_t(ch)] = float(v[ch]);
        }
    const std::vector<glm::dvec3> c = sh::projectLatLong(order, w, h, image);
    for (size_t i = 0; i < c.size(); ++i)
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(c[i][ch], truth[i][ch], 2e-3) << "coefficient " << i;
}

TEST(LatLong, BrightEastPatchPointsBandOneEast) {
    // Pins the orientation: texels a quarter across at the horizon are east (+x), so the band-1
    // vector (Y1-1, Y10, Y11) ∝ (x, y, z) must point along +x.
    const uint32_t w = 32, h = 16;
    std::vector<float> image(size_t(w) * h * 3, 0.0f);
    for (uint32_t j = 7; j <= 8; ++j)
        for (uint32_t i = 7; i <= 8; ++i)
            for (int ch = 0; ch < 3; ++ch)
                image[(size_t(j) * w + i) * 3 + size_t(ch)] = 1.0f;
    const std::vector<glm::dvec3> c = sh::projectLatLong(2, w, h, image);
    const glm::dvec3 band1(c[1].r, c[2].r, c[3].r);
    EXPECT_GT(glm::normalize(band1).x, 0.999); // symmetric patch about east: only rounding off-axis
}

} // namespace
} // namespace meadow
