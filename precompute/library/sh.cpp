#include "library/sh.h"

#include <cassert>
#include <cmath>

namespace meadow::sh {

// Associated Legendre polynomials by the stable three-term recurrence, with the factor
// (1 - Z^2)^(m/2) e^(i m phi) carried as the complex power (X + i Y)^m so that no trigonometric
// function is needed: Re and Im of that power give the cos(m phi) and sin(m phi) terms.
void evaluate(int order, const glm::dvec3& dir, double* out) {
    assert(order >= 1 && order <= kMaxOrder);
    const double X = dir.z, Y = dir.x, Z = dir.y;
    double cosTerm = 1.0, sinTerm = 0.0; // Re, Im of (X + iY)^m
    double doubleFactorial = 1.0;        // (2m - 1)!!
    for (int m = 0; m < order; ++m) {
        if (m > 0) {
            const double c = cosTerm * X - sinTerm * Y;
            sinTerm = cosTerm * Y + sinTerm * X;
            cosTerm = c;
            doubleFactorial *= double(2 * m - 1);
        }
        double pPrev = 0.0, p = doubleFactorial; // P~_{l-1}^m, P~_l^m starting at l = m
        for (int l = m; l < order; ++l) {
            if (l == m + 1) {
                pPrev = p;
                p = Z * double(2 * m + 1) * p;
            } else if (l > m + 1) {
                const double next = (double(2 * l - 1) * Z * p - double(l + m - 1) * pPrev) / double(l - m);
                pPrev = p;
                p = next;
            }
            // K_l^m = sqrt((2l + 1) / (4 pi) * (l - m)! / (l + m)!)
            double ratio = 1.0;
            for (int k = l - m + 1; k <= l + m; ++k)
                ratio /= double(k);
            const double k = std::sqrt(double(2 * l + 1) / (4.0 * M_PI) * ratio);
            if (m == 0) {
                out[index(l, 0)] = k * p;
            } else {
                out[index(l, m)] = std::sqrt(2.0) * k * p * cosTerm;
                out[index(l, -m)] = std::sqrt(2.0) * k * p * sinTerm;
            }
        }
    }
}

} // namespace meadow::sh
