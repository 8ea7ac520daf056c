// Spherical harmonics beyond evaluation (library/sh.h holds the convention and the basis):
// reconstruction, projection, rotation and zonal convolution, for the precompute.
#pragma once

#include "library/sh.h"

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace meadow::sh {

// ---------------------------------------------------------------------------------------------
// Evaluation of a coefficient vector (sh_zonal.cpp)

// Σ c_lm Y_lm(dir): the band-limited function at the unit direction `dir`.
double reconstruct(int order, std::span<const double> coefficients, const glm::dvec3& dir);
glm::dvec3 reconstructRgb(int order, std::span<const glm::dvec3> coefficients, const glm::dvec3& dir);

// ---------------------------------------------------------------------------------------------
// Projection (sh_projection.cpp)

using ScalarFunction = std::function<double(const glm::dvec3&)>;
using RgbFunction = std::function<glm::dvec3(const glm::dvec3&)>;

// A direction on the unit sphere with its share of solid angle (steradians).
struct SphereSample {
    glm::dvec3 direction;
    double weight;
};

// Gauss–Legendre nodes and weights on [-1, 1], n >= 1, by Newton iteration on P_n (Golub and
// Welsch's eigenvalue route is not needed at these sizes). Weights sum to 2.
void gaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

// Product quadrature over the band zMin <= y <= zMax of the sphere (the whole sphere by default):
// Gauss–Legendre with `latitudeNodes` nodes in y = cos(theta) times `azimuthSteps` uniform
// azimuths. Weights sum to 2 pi (zMax - zMin). Over the whole sphere it integrates exactly every
// polynomial of degree <= min(2 latitudeNodes - 1, azimuthSteps - 1); the product of two SH of
// order n needs latitudeNodes >= n and azimuthSteps >= 2n - 1. A band lets a function with a
// jump at the horizon (sky above, ground below) be integrated piece by piece without the jump
// spoiling the Gauss rule. Deterministic; no randomness.
std::vector<SphereSample> quadratureSamples(int latitudeNodes, int azimuthSteps, double zMin = -1.0, double zMax = 1.0);

// Stratified ("jittered") Monte Carlo samples: the sphere is cut into rows x 2 rows cells of equal
// area (uniform in y = cos(theta) and in azimuth), and each cell receives one uniformly
// distributed point drawn from meadow::Random(seed). 2 rows^2 samples, each of weight
// 4 pi / (2 rows^2). The same seed gives the same samples on every machine.
std::vector<SphereSample> stratifiedSamples(int rows, uint64_t seed);

// Σ_k w_k f(ω_k) Y(ω_k) over any weighted sample set.
std::vector<double> project(int order, std::span<const SphereSample> samples, const ScalarFunction& f);
std::vector<glm::dvec3> projectRgb(int order, std::span<const SphereSample> samples, const RgbFunction& f);

// Quadrature projection over the whole sphere (quadratureSamples(latitudeNodes, azimuthSteps)).
// Exact when f is band-limited to order k and 2 latitudeNodes - 1 >= k + order - 2 and
// azimuthSteps > k + order - 2 (the degree of f Y); for smooth f the error falls faster than any
// power of the node count. f with a kink or jump (a clamped cosine, a horizon) converges only
// algebraically: integrate its smooth pieces over bands with project(quadratureSamples(...)).
std::vector<double> projectQuadrature(int order, const ScalarFunction& f, int latitudeNodes, int azimuthSteps);
std::vector<glm::dvec3> projectQuadratureRgb(int order, const RgbFunction& f, int latitudeNodes, int azimuthSteps);

// Monte Carlo projection with stratifiedSamples(rows, seed), and its standard error per
// coefficient: sqrt(sample variance of 4 pi f Y / N). That is the error of plain (unstratified)
// Monte Carlo with N samples; stratification with one sample per equal-area cell never has a
// larger variance (proportional allocation), so the figure is a conservative bound.
struct MonteCarloProjection {
    std::vector<double> coefficients;
    std::vector<double> standardError;
};
struct MonteCarloProjectionRgb {
    std::vector<glm::dvec3> coefficients;
    std::vector<glm::dvec3> standardError;
};
MonteCarloProjection projectMonteCarlo(int order, const ScalarFunction& f, int rows, uint64_t seed);
MonteCarloProjectionRgb projectMonteCarloRgb(int order, const RgbFunction& f, int rows, uint64_t seed);

// Projection of a latitude-longitude (equirectangular) RGB image, laid out as light/latlong.h
// says: `rgb` holds width x height x 3 floats, row 0 at the zenith. The image is taken as
// piecewise constant over its pixels, and each pixel's integral of Y over its exact footprint on
// the sphere is evaluated with a 2 x 2 Gauss–Legendre rule in (cos theta, azimuth), so the pixel
// weights are its exact solid angles (a constant image gives c00 = 2 sqrt(pi) to rounding) and
// the basis is integrated to O(pixel^4). Rows run in parallel, summed in row order: the result
// does not depend on the thread count. Precondition: width, height >= 1, rgb.size() = 3 w h.
std::vector<glm::dvec3> projectLatLong(int order, uint32_t width, uint32_t height, std::span<const float> rgb);

// ---------------------------------------------------------------------------------------------
// Rotation (sh_rotation.cpp)

// Block-diagonal rotation of SH coefficients, one (2l+1) x (2l+1) matrix per band, built by the
// recurrence of Ivanic and Ruedenberg ("Rotation matrices for real spherical harmonics. Direct
// determination by recursion", J. Phys. Chem. 100, 1996, with the additions and corrections of
// J. Phys. Chem. A 102, 1998): band 1 is the 3 x 3 rotation itself (in this basis Y1,-1..Y1,1
// are x, y, z, so no permutation is needed), and band l follows from bands 1 and l - 1 in
// O(l^2) per band. Exact to rounding for every order.
//
// Meaning: if c are the coefficients of f, apply(c) gives the coefficients of the rotated
// function g(ω) = f(Rᵀ ω), i.e. f carried along by R (a light at direction s moves to R s).
struct Rotation {
    int order = 0;
    std::vector<double> bands; // band l's matrix, row-major, at offset Σ_{k<l} (2k+1)^2
};
// Precondition: `rotation` orthonormal with determinant +1 (asserted to 1e-6).
Rotation makeRotation(int order, const glm::dmat3& rotation);
void apply(const Rotation& rotation, std::span<const double> in, std::span<double> out);
void applyRgb(const Rotation& rotation, std::span<const glm::dvec3> in, std::span<glm::dvec3> out);
std::vector<double> rotate(int order, std::span<const double> coefficients, const glm::dmat3& rotation);
std::vector<glm::dvec3> rotateRgb(int order, std::span<const glm::dvec3> coefficients, const glm::dmat3& rotation);

// ---------------------------------------------------------------------------------------------
// Zonal harmonics, convolution, irradiance (sh_zonal.cpp)

// A zonal function (symmetric about +y) is given by its m = 0 coefficients, one per band:
// zonal[l] = c_l0. These helpers take and return `order` band values.

// Coefficients of max(cos theta, 0) about +y: 0.886227, 1.023327, 0.495416, 0, -0.110778, ...
// (Ramamoorthi and Hanrahan 2001, eq. 8: A_l = sqrt(4 pi / (2l + 1)) z_l = pi, 2 pi / 3, pi / 4,
// 0, -pi / 24, ...; zero for odd l > 1).
std::vector<double> clampedCosineZonal(int order);

// The zonal function turned so that its axis (+y) points along the unit vector `axis`: by the
// addition theorem, c_lm = sqrt(4 pi / (2l + 1)) zonal[l] Y_lm(axis).
std::vector<double> rotateZonal(int order, std::span<const double> zonal, const glm::dvec3& axis);

// Funk–Hecke: the convolution (h * f)(ω) = ∫ h(ω · ω') f(ω') dω' of f with the zonal kernel h
// scales band l by sqrt(4 pi / (2l + 1)) h_l.
std::vector<double> convolveZonal(int order, std::span<const double> coefficients, std::span<const double> kernel);
std::vector<glm::dvec3> convolveZonalRgb(int order, std::span<const glm::dvec3> coefficients,
                                         std::span<const double> kernel);

// Irradiance E(n) = ∫ L(ω) max(n · ω, 0) dω from radiance coefficients (Ramamoorthi and Hanrahan
// 2001): the convolution with the clamped cosine. reconstruct() of the result at a unit normal n
// gives the irradiance there; at order 3 the error is below ~3 % for any lighting (their §3).
std::vector<double> irradiance(int order, std::span<const double> radiance);
std::vector<glm::dvec3> irradianceRgb(int order, std::span<const glm::dvec3> radiance);

// Coefficients of a directional light: radiance δ(ω, direction) scaled so that a surface facing
// it receives irradiance 1, i.e. c_lm = Y_lm(direction). Scale by the light's irradiance (for the
// sun: its radiance times its solid angle).
std::vector<double> directionalLight(int order, const glm::dvec3& direction);

} // namespace meadow::sh
