// Rotation of real SH coefficients by the recurrence of Ivanic and Ruedenberg (J. Phys. Chem. 100,
// 1996; corrections in J. Phys. Chem. A 102, 1998). Band l's matrix is built from band 1 (the
// 3 x 3 rotation) and band l - 1 through the helper functions P, U, V, W of their Table 2.
//
// Why this works unchanged in meadow's basis: the recurrence only sees the band-1 matrix, and is
// covariant under the axis relabelling and the phase convention as long as band 1 is expressed in
// the same basis. meadow's band 1 is (Y1-1, Y10, Y11) = 0.488603 (x, y, z) with no Condon–Shortley
// phase, which is Ivanic and Ruedenberg's real basis (their (y, z, x) order) read in the rotated
// frame (X, Y, Z) = (z, x, y) of sh.h; so band 1's matrix is the world rotation R itself, rows and
// columns in (x, y, z) order. tests/precompute/light/test_sh.cpp checks every order against projection of
// the rotated function.
#include "light/sh.h"

#include <cassert>
#include <cmath>

namespace meadow::sh {
namespace {

size_t bandOffset(int l) {
    size_t offset = 0;
    for (int k = 0; k < l; ++k)
        offset += size_t(2 * k + 1) * size_t(2 * k + 1);
    return offset;
}

// Element (m, n), -l <= m, n <= l, of a band matrix stored row-major.
struct BandMatrix {
    double* data;
    int l;
    double& operator()(int m, int n) const { return data[size_t(m + l) * size_t(2 * l + 1) + size_t(n + l)]; }
};

// Ivanic and Ruedenberg's P^i_{a,b} for band l, from band 1 (r1) and band l - 1 (previous).
double functionP(int i, int a, int b, int l, const BandMatrix& r1, const BandMatrix& previous) {
    if (b == l)
        return r1(i, 1) * previous(a, l - 1) - r1(i, -1) * previous(a, -l + 1);
    if (b == -l)
        return r1(i, 1) * previous(a, -l + 1) + r1(i, -1) * previous(a, l - 1);
    return r1(i, 0) * previous(a, b);
}

double functionU(int m, int n, int l, const BandMatrix& r1, const BandMatrix& previous) {
    return functionP(0, m, n, l, r1, previous);
}

double functionV(int m, int n, int l, const BandMatrix& r1, const BandMatrix& previous) {
    if (m == 0)
        return functionP(1, 1, n, l, r1, previous) + functionP(-1, -1, n, l, r1, previous);
    if (m > 0) {
        const double delta = m == 1 ? 1.0 : 0.0;
        return functionP(1, m - 1, n, l, r1, previous) * std::sqrt(1.0 + delta) -
               (m == 1 ? 0.0 : functionP(-1, -m + 1, n, l, r1, previous));
    }
    // m < 0. The 1996 paper prints (1 + δ) and sqrt(1 - δ) here; the 1998 correction swaps them so
    // that the sqrt(2) appears at m = -1, mirroring the m = 1 case above.
    const double delta = m == -1 ? 1.0 : 0.0;
    return (m == -1 ? 0.0 : functionP(1, m + 1, n, l, r1, previous)) +
           functionP(-1, -m - 1, n, l, r1, previous) * std::sqrt(1.0 + delta);
}

double functionW(int m, int n, int l, const BandMatrix& r1, const BandMatrix& previous) {
    // Only called where the coefficient w is non-zero: 0 < |m| < l - 1.
    if (m > 0)
        return functionP(1, m + 1, n, l, r1, previous) + functionP(-1, -m - 1, n, l, r1, previous);
    return functionP(1, m - 1, n, l, r1, previous) - functionP(-1, -m + 1, n, l, r1, previous);
}

void buildBand(int l, const BandMatrix& r1, const BandMatrix& previous, const BandMatrix& out) {
    for (int m = -l; m <= l; ++m)
        for (int n = -l; n <= l; ++n) {
            const int absM = std::abs(m);
            const double delta = m == 0 ? 1.0 : 0.0;
            const double denominator = std::abs(n) == l ? double(2 * l * (2 * l - 1)) : double((l + n) * (l - n));
            // The coefficients u, v, w of Table 1; each helper is evaluated only where its
            // coefficient is non-zero, since elsewhere it would index outside band l - 1.
            double value = 0.0;
            if (absM < l)
                value += std::sqrt(double((l + m) * (l - m)) / denominator) * functionU(m, n, l, r1, previous);
            const double v = 0.5 * std::sqrt((1.0 + delta) * double((l + absM - 1) * (l + absM)) / denominator) *
                             (1.0 - 2.0 * delta);
            value += v * functionV(m, n, l, r1, previous);
            if (m != 0 && absM < l - 1) {
                const double w = -0.5 * std::sqrt(double((l - absM - 1) * (l - absM)) / denominator);
                value += w * functionW(m, n, l, r1, previous);
            }
            out(m, n) = value;
        }
}

} // namespace

Rotation makeRotation(int order, const glm::dmat3& rotation) {
    assert(order >= 1 && order <= kMaxOrder);
    [[maybe_unused]] const glm::dmat3 gram = glm::transpose(rotation) * rotation;
    for ([[maybe_unused]] int c = 0; c < 3; ++c)
        for ([[maybe_unused]] int r = 0; r < 3; ++r)
            assert(std::abs(gram[c][r] - (c == r ? 1.0 : 0.0)) < 1e-6);
    assert(glm::determinant(rotation) > 0.0);

    Rotation result;
    result.order = order;
    result.bands.assign(bandOffset(order), 0.0);
    result.bands[0] = 1.0;
    if (order == 1)
        return result;
    // Band 1: element (m, n) is R[row m + 1][column n + 1]; glm stores columns first.
    const BandMatrix r1{&result.bands[bandOffset(1)], 1};
    for (int m = -1; m <= 1; ++m)
        for (int n = -1; n <= 1; ++n)
            r1(m, n) = rotation[n + 1][m + 1];
    for (int l = 2; l < order; ++l)
        buildBand(l, r1, BandMatrix{&result.bands[bandOffset(l - 1)], l - 1},
                  BandMatrix{&result.bands[bandOffset(l)], l});
    return result;
}

namespace {

template <typename Value> void applyBands(const Rotation& rotation, std::span<const Value> in, std::span<Value> out) {
    assert(in.size() == size_t(coefficientCount(rotation.order)) && out.size() == in.size());
    assert(in.data() != out.data());
    size_t offset = 0;
    for (int l = 0; l < rotation.order; ++l) {
        const int size = 2 * l + 1, first = index(l, -l);
        for (int row = 0; row < size; ++row) {
            Value sum(0.0);
            for (int column = 0; column < size; ++column)
                sum += in[size_t(first + column)] * rotation.bands[offset + size_t(row * size + column)];
            out[size_t(first + row)] = sum;
        }
        offset += size_t(size) * size_t(size);
    }
}

} // namespace

void apply(const Rotation& rotation, std::span<const double> in, std::span<double> out) {
    applyBands<double>(rotation, in, out);
}

void applyRgb(const Rotation& rotation, std::span<const glm::dvec3> in, std::span<glm::dvec3> out) {
    applyBands<glm::dvec3>(rotation, in, out);
}

std::vector<double> rotate(int order, std::span<const double> coefficients, const glm::dmat3& rotation) {
    std::vector<double> out(coefficients.size());
    apply(makeRotation(order, rotation), coefficients, out);
    return out;
}

std::vector<glm::dvec3> rotateRgb(int order, std::span<const glm::dvec3> coefficients, const glm::dmat3& rotation) {
    std::vector<glm::dvec3> out(coefficients.size());
    applyRgb(makeRotation(order, rotation), coefficients, out);
    return out;
}

} // namespace meadow::sh
