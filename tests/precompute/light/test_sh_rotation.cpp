// Rotation of SH coefficients (Ivanic and Ruedenberg recurrence, light/sh_rotation.cpp): rotating
// coefficients equals projecting the rotated function, for every order up to kMaxOrder.
#include "core/random.h"
#include "light/sh.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace meadow {
namespace {

// A uniformly distributed rotation: a unit quaternion from a uniform point in the 4-ball.
glm::dmat3 randomRotation(Random& random) {
    for (;;) {
        const glm::dquat q(random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f),
                           random.uniform(-1.0f, 1.0f));
        const double length = glm::length(q);
        if (length > 0.1 && length <= 1.0)
            return glm::mat3_cast(q / length);
    }
}

std::vector<double> randomCoefficients(Random& random, int order) {
    std::vector<double> c(size_t(sh::coefficientCount(order)));
    for (double& v : c)
        v = random.uniform(-1.0f, 1.0f);
    return c;
}

// Coefficients of g(ω) = f(Rᵀ ω) by exact quadrature: g is band-limited to the same order, so
// order + 1 Gauss nodes and 2 order + 1 azimuths integrate g Y exactly.
std::vector<double> projectRotated(int order, const std::vector<double>& c, const glm::dmat3& rotation) {
    const glm::dmat3 inverse = glm::transpose(rotation);
    return sh::projectQuadrature(
        order, [&](const glm::dvec3& d) { return sh::reconstruct(order, c, inverse * d); }, order + 1, 2 * order + 1);
}

TEST(ShRotation, EqualsProjectionOfTheRotatedFunctionAtEveryOrder) {
    Random random(42);
    for (int order = 1; order <= sh::kMaxOrder; ++order)
        for (int trial = 0; trial < 4; ++trial) {
            const glm::dmat3 rotation = randomRotation(random);
            const std::vector<double> c = randomCoefficients(random, order);
            const std::vector<double> rotated = sh::rotate(order, c, rotation);
            const std::vector<double> expected = projectRotated(order, c, rotation);
            for (size_t i = 0; i < c.size(); ++i)
                // Tolerance: exact quadrature and an exact recurrence; rounding of a few hundred
                // terms of size ~1 remains.
                EXPECT_NEAR(rotated[i], expected[i], 1e-10) << "order " << order << " trial " << trial << " i " << i;
        }
}

TEST(ShRotation, AxisRotationsOfTheFullOrder) {
    // Quarter turns about each axis are the cases where a wrong sign or an index swap in one
    // branch of the recurrence cannot hide behind a generic rotation's mixing.
    const int order = sh::kMaxOrder;
    Random random(9);
    const std::vector<double> c = randomCoefficients(random, order);
    for (const glm::dvec3 axis : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)})
        for (const double angle : {M_PI / 2, M_PI, 0.3}) {
            const glm::dmat3 rotation = glm::mat3_cast(glm::angleAxis(angle, axis));
            const std::vector<double> rotated = sh::rotate(order, c, rotation);
            const std::vector<double> expected = projectRotated(order, c, rotation);
            for (size_t i = 0; i < c.size(); ++i)
                EXPECT_NEAR(rotated[i], expected[i], 1e-10) << "axis " << axis.x << axis.y << axis.z << " i " << i;
        }
}

TEST(ShRotation, MovesADirectionalLightAlongWithTheRotation) {
    Random random(4);
    for (int trial = 0; trial < 5; ++trial) {
        const glm::dmat3 rotation = randomRotation(random);
        const glm::dvec3 light = glm::normalize(glm::dvec3(0.2, -0.5, 0.8));
        const std::vector<double> moved =
            sh::rotate(sh::kMaxOrder, sh::directionalLight(sh::kMaxOrder, light), rotation);
        const std::vector<double> expected = sh::directionalLight(sh::kMaxOrder, rotation * light);
        for (size_t i = 0; i < moved.size(); ++i)
            EXPECT_NEAR(moved[i], expected[i], 1e-11) << "trial " << trial << " i " << i; // rounding only
    }
}

TEST(ShRotation, ComposesPreservesEnergyAndRgbIsPerChannel) {
    Random random(77);
    const int order = 6;
    const glm::dmat3 a = randomRotation(random), b = randomRotation(random);
    const std::vector<double> c = randomCoefficients(random, order);
    const std::vector<double> twice = sh::rotate(order, sh::rotate(order, c, a), b);
    const std::vector<double> once = sh::rotate(order, c, b * a);
    double before = 0.0, after = 0.0;
    for (size_t i = 0; i < c.size(); ++i) {
        EXPECT_NEAR(twice[i], once[i], 1e-12); // rounding only
        before += c[i] * c[i];
        after += once[i] * once[i];
    }
    // Each band's matrix is orthogonal, so the L2 norm of the function is kept.
    EXPECT_NEAR(after, before, 1e-11);

    std::vector<glm::dvec3> rgb(c.size());
    for (size_t i = 0; i < c.size(); ++i)
        rgb[i] = glm::dvec3(c[i], 2.0 * c[i], -c[i]);
    const std::vector<glm::dvec3> rotatedRgb = sh::rotateRgb(order, rgb, a);
    const std::vector<double> rotated = sh::rotate(order, c, a);
    for (size_t i = 0; i < c.size(); ++i) {
        EXPECT_NEAR(rotatedRgb[i].r, rotated[i], 1e-14);
        EXPECT_NEAR(rotatedRgb[i].g, 2.0 * rotated[i], 1e-14);
        EXPECT_NEAR(rotatedRgb[i].b, -rotated[i], 1e-14);
    }

    const std::vector<double> identity = sh::rotate(order, c, glm::dmat3(1.0));
    for (size_t i = 0; i < c.size(); ++i)
        EXPECT_NEAR(identity[i], c[i], 1e-15);
}

TEST(ShRotation, ZonalRotationAgreesWithGeneralRotation) {
    // rotateZonal(z, axis) is the zonal function turned from +y to `axis`; so is the general
    // rotation of its coefficient vector by any R with R (0, 1, 0) = axis.
    const int order = sh::kMaxOrder;
    const std::vector<double> zonal = sh::clampedCosineZonal(order);
    std::vector<double> full(size_t(sh::coefficientCount(order)), 0.0);
    for (int l = 0; l < order; ++l)
        full[size_t(sh::index(l, 0))] = zonal[size_t(l)];
    Random random(21);
    for (int trial = 0; trial < 4; ++trial) {
        const glm::dmat3 rotation = randomRotation(random);
        const std::vector<double> general = sh::rotate(order, full, rotation);
        const std::vector<double> turned = sh::rotateZonal(order, zonal, rotation * glm::dvec3(0, 1, 0));
        for (size_t i = 0; i < full.size(); ++i)
            EXPECT_NEAR(turned[i], general[i], 1e-12) << "trial " << trial << " i " << i; // rounding only
    }
}

} // namespace
} // namespace meadow
