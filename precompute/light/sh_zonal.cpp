// Zonal harmonics, Funk–Hecke convolution, irradiance environment maps (Ramamoorthi and Hanrahan
// 2001), directional lights and evaluation of coefficient vectors.
#include "light/sh.h"

#include <cassert>
#include <cmath>

namespace meadow::sh {
namespace {

// sqrt(4 pi / (2l + 1)): the factor that turns a zonal coefficient into the Funk–Hecke eigenvalue
// (and Y_l0 at the pole into 1).
double bandScale(int l) {
    return std::sqrt(4.0 * M_PI / double(2 * l + 1));
}

double factorial(int n) {
    double result = 1.0;
    for (int k = 2; k <= n; ++k)
        result *= double(k);
    return result;
}

// Ramamoorthi and Hanrahan 2001, eq. 8: the Funk–Hecke eigenvalue A_l of the clamped cosine.
double clampedCosineEigenvalue(int l) {
    if (l == 0)
        return M_PI;
    if (l == 1)
        return 2.0 * M_PI / 3.0;
    if (l % 2 == 1)
        return 0.0;
    const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
    const double half = factorial(l / 2);
    return 2.0 * M_PI * sign / double((l + 2) * (l - 1)) * factorial(l) / (std::pow(2.0, l) * half * half);
}

template <typename Value>
std::vector<Value> convolve(int order, std::span<const Value> coefficients, std::span<const double> kernel) {
    assert(order >= 1 && order <= kMaxOrder);
    assert(coefficients.size() == size_t(coefficientCount(order)) && kernel.size() == size_t(order));
    std::vector<Value> out(coefficients.begin(), coefficients.end());
    for (int l = 0; l < order; ++l) {
        const double scale = bandScale(l) * kernel[size_t(l)];
        for (int m = -l; m <= l; ++m)
            out[size_t(index(l, m))] *= scale;
    }
    return out;
}

} // namespace

double reconstruct(int order, std::span<const double> coefficients, const glm::dvec3& dir) {
    assert(order >= 1 && order <= kMaxOrder && coefficients.size() == size_t(coefficientCount(order)));
    double basis[kMaxOrder * kMaxOrder];
    evaluate(order, dir, basis);
    double sum = 0.0;
    for (size_t i = 0; i < coefficients.size(); ++i)
        sum += coefficients[i] * basis[i];
    return sum;
}

glm::dvec3 reconstructRgb(int order, std::span<const glm::dvec3> coefficients, const glm::dvec3& dir) {
    assert(order >= 1 && order <= kMaxOrder && coefficients.size() == size_t(coefficientCount(order)));
    double basis[kMaxOrder * kMaxOrder];
    evaluate(order, dir, basis);
    glm::dvec3 sum(0.0);
    for (size_t i = 0; i < coefficients.size(); ++i)
        sum += coefficients[i] * basis[i];
    return sum;
}

std::vector<double> clampedCosineZonal(int order) {
    assert(order >= 1 && order <= kMaxOrder);
    std::vector<double> zonal(static_cast<size_t>(order));
    for (int l = 0; l < order; ++l)
        zonal[size_t(l)] = clampedCosineEigenvalue(l) / bandScale(l);
    return zonal;
}

std::vector<double> rotateZonal(int order, std::span<const double> zonal, const glm::dvec3& axis) {
    assert(order >= 1 && order <= kMaxOrder && zonal.size() == size_t(order));
    std::vector<double> coefficients(size_t(coefficientCount(order)));
    evaluate(order, axis, coefficients.data());
    for (int l = 0; l < order; ++l) {
        const double scale = bandScale(l) * zonal[size_t(l)];
        for (int m = -l; m <= l; ++m)
            coefficients[size_t(index(l, m))] *= scale;
    }
    return coefficients;
}

std::vector<double> convolveZonal(int order, std::span<const double> coefficients, std::span<const double> kernel) {
    return convolve<double>(order, coefficients, kernel);
}

std::vector<glm::dvec3> convolveZonalRgb(int order, std::span<const glm::dvec3> coefficients,
                                         std::span<const double> kernel) {
    return convolve<glm::dvec3>(order, coefficients, kernel);
}

std::vector<double> irradiance(int order, std::span<const double> radiance) {
    return convolveZonal(order, radiance, clampedCosineZonal(order));
}

std::vector<glm::dvec3> irradianceRgb(int order, std::span<const glm::dvec3> radiance) {
    return convolveZonalRgb(order, radiance, clampedCosineZonal(order));
}

std::vector<double> directionalLight(int order, const glm::dvec3& direction) {
    assert(order >= 1 && order <= kMaxOrder);
    std::vector<double> coefficients(size_t(coefficientCount(order)));
    evaluate(order, direction, coefficients.data());
    return coefficients;
}

} // namespace meadow::sh
