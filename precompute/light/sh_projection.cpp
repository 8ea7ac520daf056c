// Projection of functions and images onto the SH basis: Gauss–Legendre product quadrature,
// stratified Monte Carlo, and latitude-longitude images with exact pixel solid angles.
#include "core/random.h"
#include "light/latlong.h"
#include "light/sh.h"

#include <tbb/parallel_for.h>

#include <cassert>
#include <cmath>

namespace meadow::sh {
namespace {

glm::dvec3 directionFrom(double y, double phi) {
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - y * y));
    return {sinTheta * std::sin(phi), y, sinTheta * std::cos(phi)};
}

// Σ_k w_k f(ω_k) Y(ω_k), for one channel (double) or three (glm::dvec3).
template <typename Value, typename Function>
std::vector<Value> projectSamples(int order, std::span<const SphereSample> samples, const Function& f) {
    assert(order >= 1 && order <= kMaxOrder);
    const int n = coefficientCount(order);
    std::vector<Value> coefficients(size_t(n), Value(0.0));
    double basis[kMaxOrder * kMaxOrder];
    for (const SphereSample& sample : samples) {
        evaluate(order, sample.direction, basis);
        const Value weighted = f(sample.direction) * sample.weight;
        for (int i = 0; i < n; ++i)
            coefficients[size_t(i)] += weighted * basis[i];
    }
    return coefficients;
}

// Monte Carlo with equal weights 4 pi / N: the mean of g_k = 4 pi f(ω_k) Y(ω_k) and the standard
// error of that mean, sqrt(sample variance / N), per channel.
template <typename Value, typename Function>
void projectWithError(int order, const Function& f, int rows, uint64_t seed, std::vector<Value>& coefficients,
                      std::vector<Value>& standardError) {
    assert(order >= 1 && order <= kMaxOrder && rows >= 1);
    const std::vector<SphereSample> samples = stratifiedSamples(rows, seed);
    const int n = coefficientCount(order);
    const double count = double(samples.size());
    std::vector<Value> sum(size_t(n), Value(0.0)), sumSquares(size_t(n), Value(0.0));
    double basis[kMaxOrder * kMaxOrder];
    for (const SphereSample& sample : samples) {
        evaluate(order, sample.direction, basis);
        const Value value = f(sample.direction) * (4.0 * M_PI);
        for (int i = 0; i < n; ++i) {
            const Value g = value * basis[i];
            sum[size_t(i)] += g;
            sumSquares[size_t(i)] += g * g;
        }
    }
    coefficients.resize(size_t(n));
    standardError.resize(size_t(n));
    for (size_t i = 0; i < size_t(n); ++i) {
        const Value mean = sum[i] / count;
        // Unbiased sample variance; clamped because rounding can push a zero variance below 0.
        const Value variance = glm::max((sumSquares[i] - mean * mean * count) / std::max(count - 1.0, 1.0), Value(0.0));
        coefficients[i] = mean;
        standardError[i] = glm::sqrt(variance / count);
    }
}

} // namespace

void gaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
    assert(n >= 1);
    nodes.assign(size_t(n), 0.0);
    weights.assign(size_t(n), 0.0);
    for (int i = 0; i < n; ++i) {
        // Tricomi's initial guess for the i-th largest root; Newton converges in a few steps.
        double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));
        double derivative = 1.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1.0, p1 = x; // P_{k-1}, P_k by Bonnet's recurrence
            for (int k = 2; k <= n; ++k) {
                const double p2 = (double(2 * k - 1) * x * p1 - double(k - 1) * p0) / double(k);
                p0 = p1;
                p1 = p2;
            }
            derivative = double(n) * (x * p1 - p0) / (x * x - 1.0);
            const double step = p1 / derivative;
            x -= step;
            if (std::abs(step) < 1e-15)
                break;
        }
        // Recompute P_n' at the converged root for the weight 2 / ((1 - x^2) P_n'(x)^2).
        double p0 = 1.0, p1 = x;
        for (int k = 2; k <= n; ++k) {
            const double p2 = (double(2 * k - 1) * x * p1 - double(k - 1) * p0) / double(k);
            p0 = p1;
            p1 = p2;
        }
        derivative = double(n) * (x * p1 - p0) / (x * x - 1.0);
        nodes[size_t(i)] = x;
        weights[size_t(i)] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
}

std::vector<SphereSample> quadratureSamples(int latitudeNodes, int azimuthSteps, double zMin, double zMax) {
    assert(latitudeNodes >= 1 && azimuthSteps >= 1 && -1.0 <= zMin && zMin < zMax && zMax <= 1.0);
    std::vector<double> nodes, weights;
    gaussLegendre(latitudeNodes, nodes, weights);
    const double middle = 0.5 * (zMax + zMin), half = 0.5 * (zMax - zMin);
    const double azimuthWeight = 2.0 * M_PI / double(azimuthSteps);
    std::vector<SphereSample> samples;
    samples.reserve(size_t(latitudeNodes) * size_t(azimuthSteps));
    for (int i = 0; i < latitudeNodes; ++i) {
        const double y = middle + half * nodes[size_t(i)];
        for (int s = 0; s < azimuthSteps; ++s) {
            const double phi = 2.0 * M_PI * (double(s) + 0.5) / double(azimuthSteps);
            samples.push_back({directionFrom(y, phi), half * weights[size_t(i)] * azimuthWeight});
        }
    }
    return samples;
}

std::vector<SphereSample> stratifiedSamples(int rows, uint64_t seed) {
    assert(rows >= 1);
    const int columns = 2 * rows;
    const double weight = 4.0 * M_PI / double(rows * columns);
    Random random(seed);
    std::vector<SphereSample> samples;
    samples.reserve(size_t(rows) * size_t(columns));
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < columns; ++j) {
            // Uniform in y and in azimuth is uniform in solid angle (Archimedes' hat-box theorem).
            const double y = -1.0 + 2.0 * (double(i) + double(random.uniform())) / double(rows);
            const double phi = 2.0 * M_PI * (double(j) + double(random.uniform())) / double(columns);
            samples.push_back({directionFrom(y, phi), weight});
        }
    return samples;
}

std::vector<double> project(int order, std::span<const SphereSample> samples, const ScalarFunction& f) {
    return projectSamples<double>(order, samples, f);
}

std::vector<glm::dvec3> projectRgb(int order, std::span<const SphereSample> samples, const RgbFunction& f) {
    return projectSamples<glm::dvec3>(order, samples, f);
}

std::vector<double> projectQuadrature(int order, const ScalarFunction& f, int latitudeNodes, int azimuthSteps) {
    return project(order, quadratureSamples(latitudeNodes, azimuthSteps), f);
}

std::vector<glm::dvec3> projectQuadratureRgb(int order, const RgbFunction& f, int latitudeNodes, int azimuthSteps) {
    return projectRgb(order, quadratureSamples(latitudeNodes, azimuthSteps), f);
}

MonteCarloProjection projectMonteCarlo(int order, const ScalarFunction& f, int rows, uint64_t seed) {
    MonteCarloProjection result;
    projectWithError<double>(order, f, rows, seed, result.coefficients, result.standardError);
    return result;
}

MonteCarloProjectionRgb projectMonteCarloRgb(int order, const RgbFunction& f, int rows, uint64_t seed) {
    MonteCarloProjectionRgb result;
    projectWithError<glm::dvec3>(order, f, rows, seed, result.coefficients, result.standardError);
    return result;
}

std::vector<glm::dvec3> projectLatLong(int order, uint32_t width, uint32_t height, std::span<const float> rgb) {
    assert(order >= 1 && order <= kMaxOrder && width >= 1 && height >= 1);
    assert(rgb.size() == size_t(width) * height * 3);
    const int n = coefficientCount(order);
    // Two Gauss–Legendre points per pixel along each axis: x = mid ± half / sqrt(3), weight half.
    const double offset = 1.0 / std::sqrt(3.0);
    const double halfAzimuth = M_PI / double(width);
    std::vector<double> sinPhi(size_t(width) * 2), cosPhi(size_t(width) * 2);
    for (uint32_t i = 0; i < width; ++i)
        for (int k = 0; k < 2; ++k) {
            const double phi = halfAzimuth * (2.0 * double(i) + 1.0 + (k == 0 ? -offset : offset));
            sinPhi[size_t(i) * 2 + size_t(k)] = std::sin(phi);
            cosPhi[size_t(i) * 2 + size_t(k)] = std::cos(phi);
        }
    std::vector<glm::dvec3> rowSums(size_t(height) * size_t(n), glm::dvec3(0.0));
    tbb::parallel_for(uint32_t(0), height, [&](uint32_t j) {
        const double top = latLongRowTopCosine(j, height), bottom = latLongRowTopCosine(j + 1, height);
        const double middle = 0.5 * (top + bottom), half = 0.5 * (top - bottom);
        const double weight = half * halfAzimuth; // each of the 4 points of a pixel
        glm::dvec3* sums = &rowSums[size_t(j) * size_t(n)];
        double basis[kMaxOrder * kMaxOrder];
        for (uint32_t i = 0; i < width; ++i) {
            const float* texel = &rgb[(size_t(j) * width + i) * 3];
            const glm::dvec3 value = glm::dvec3(texel[0], texel[1], texel[2]) * weight;
            for (int a = 0; a < 2; ++a) {
                const double y = middle + (a == 0 ? -offset : offset) * half;
                const double sinTheta = std::sqrt(std::max(0.0, 1.0 - y * y));
                for (int b = 0; b < 2; ++b) {
                    const size_t column = size_t(i) * 2 + size_t(b);
                    evaluate(order, {sinTheta * sinPhi[column], y, sinTheta * cosPhi[column]}, basis);
                    for (int c = 0; c < n; ++c)
                        sums[c] += value * basis[c];
                }
            }
        }
    });
    std::vector<glm::dvec3> coefficients(size_t(n), glm::dvec3(0.0));
    for (uint32_t j = 0; j < height; ++j)
        for (int c = 0; c < n; ++c)
            coefficients[size_t(c)] += rowSums[size_t(j) * size_t(n) + size_t(c)];
    return coefficients;
}

} // namespace meadow::sh
