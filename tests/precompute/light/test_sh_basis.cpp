// The SH basis: the explicit order-3 polynomials of light/sh.h, and orthonormality of every order
// up to kMaxOrder under a product Gauss–Legendre x uniform-azimuth quadrature.
#include "light/sh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace meadow {
namespace {

TEST(ShBasis, MatchesTheDocumentedOrder3Polynomials) {
    const glm::dvec3 dirs[] = {
        glm::normalize(glm::dvec3(0.3, 0.8, -0.5)), {0, 1, 0}, {1, 0, 0}, glm::normalize(glm::dvec3(-0.7, -0.2, 0.6))};
    for (const glm::dvec3& d : dirs) {
        double y[9];
        sh::evaluate(3, d, y);
        const double x = d.x, yy = d.y, z = d.z;
        const double expected[9] = {0.282095,
                                    0.488603 * x,
                                    0.488603 * yy,
                                    0.488603 * z,
                                    1.092548 * x * z,
                                    1.092548 * x * yy,
                                    0.315392 * (3 * yy * yy - 1),
                                    1.092548 * yy * z,
                                    0.546274 * (z * z - x * x)};
        // Tolerance: the constants above are printed to 6 digits.
        for (int i = 0; i < 9; ++i)
            EXPECT_NEAR(y[i], expected[i], 2e-6) << "coefficient " << i;
    }
}

TEST(ShBasis, OrthonormalUpToMaxOrder) {
    // Gauss–Legendre in cos(theta) with 2 * kMaxOrder nodes is exact for the polynomial degree of
    // a product of two basis functions; the azimuth with 4 * kMaxOrder uniform steps likewise.
    const int order = sh::kMaxOrder, n = sh::coefficientCount(order);
    const int nodes = 2 * order, steps = 4 * order;
    // Gauss–Legendre nodes and weights by Newton iteration on P_nodes.
    std::vector<double> mu(nodes), w(nodes);
    for (int i = 0; i < nodes; ++i) {
        double x = std::cos(M_PI * (i + 0.75) / (nodes + 0.5));
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= nodes; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            const double dp = nodes * (x * p1 - p0) / (x * x - 1);
            x -= p1 / dp;
            if (it == 99) {
                mu[i] = x;
                w[i] = 2.0 / ((1 - x * x) * dp * dp);
            }
        }
    }
    std::vector<double> gram(size_t(n) * n, 0.0), y(n);
    for (int i = 0; i < nodes; ++i)
        for (int s = 0; s < steps; ++s) {
            const double phi = 2 * M_PI * s / steps, sinTheta = std::sqrt(1 - mu[i] * mu[i]);
            sh::evaluate(order, {sinTheta * std::sin(phi), mu[i], sinTheta * std::cos(phi)}, y.data());
            const double weight = w[i] * 2 * M_PI / steps;
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b)
                    gram[size_t(a) * n + b] += weight * y[a] * y[b];
        }
    // Tolerance: the quadrature is exact; what remains is double rounding over 1,024 samples.
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            EXPECT_NEAR(gram[size_t(a) * n + b], a == b ? 1.0 : 0.0, 1e-9) << a << "," << b;
}

} // namespace
} // namespace meadow
