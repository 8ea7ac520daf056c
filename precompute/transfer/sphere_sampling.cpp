#include "transfer/sphere_sampling.h"

#include "core/random.h"
#include "light/sh.h"
#include "transfer/transfer.h"

#include <cassert>
#include <cmath>
#include <numbers>

namespace meadow::transfer {

namespace {

// Azimuth step of the Fibonacci lattice: 2 pi / golden ratio^2, the most irrational turn, so no
// two points line up in azimuth.
constexpr double kGoldenTurn = 2.0 * std::numbers::pi * (1.0 - 1.0 / std::numbers::phi);

glm::dvec3 fromHeightAndAzimuth(double y, double azimuth) {
    const double radius = std::sqrt(std::max(0.0, 1.0 - y * y));
    return {radius * std::cos(azimuth), y, radius * std::sin(azimuth)};
}

// Stream `stream` of `seed`, hashed so neighbouring streams share no numbers.
Random streamRandom(uint64_t seed, uint64_t stream) {
    return Random(splitMix64(seed ^ splitMix64(stream + 0x5eed5eed5eedull)));
}

// 53-bit uniform in [0, 1): rotations want more resolution than Random::uniform's 24 bits.
double uniform53(Random& random) {
    return double(random.next() >> 11) * (1.0 / 9007199254740992.0);
}

} // namespace

std::vector<glm::dvec3> sphericalFibonacci(uint32_t count) {
    std::vector<glm::dvec3> points(count);
    for (uint32_t i = 0; i < count; ++i) {
        const double y = 1.0 - (2.0 * double(i) + 1.0) / double(count);
        points[i] = fromHeightAndAzimuth(y, kGoldenTurn * double(i));
    }
    return points;
}

std::vector<glm::dvec3> hemisphericalFibonacci(uint32_t count) {
    std::vector<glm::dvec3> points(count);
    for (uint32_t i = 0; i < count; ++i) {
        const double y = 1.0 - (double(i) + 0.5) / double(count);
        points[i] = fromHeightAndAzimuth(y, kGoldenTurn * double(i));
    }
    return points;
}

glm::dmat3 randomRotation(uint64_t seed, uint64_t stream) {
    Random random = streamRandom(seed, stream);
    const double u1 = uniform53(random), u2 = uniform53(random), u3 = uniform53(random);
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    const double t2 = 2.0 * std::numbers::pi * u2, t3 = 2.0 * std::numbers::pi * u3;
    const double x = a * std::sin(t2), y = a * std::cos(t2), z = b * std::sin(t3), w = b * std::cos(t3);
    // Rotation matrix of the unit quaternion (w, x, y, z), columns first as glm stores them.
    return glm::dmat3(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y), //
                      2.0 * (x * y - w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + w * x), //
                      2.0 * (x * z + w * y), 2.0 * (y * z - w * x), 1.0 - 2.0 * (x * x + y * y));
}

glm::dmat3 randomAzimuthRotation(uint64_t seed, uint64_t stream) {
    Random random = streamRandom(seed, stream);
    const double angle = 2.0 * std::numbers::pi * uniform53(random);
    const double c = std::cos(angle), s = std::sin(angle);
    return glm::dmat3(c, 0.0, -s,    //
                      0.0, 1.0, 0.0, //
                      s, 0.0, c);
}

double lambertWeight(int l) {
    assert(l >= 0);
    if (l == 0)
        return std::numbers::pi;
    if (l == 1)
        return 2.0 * std::numbers::pi / 3.0;
    if (l % 2 == 1)
        return 0.0;
    // l! / (2^l ((l/2)!)^2) by its product form, exact for the small l of SH bands.
    double ratio = 1.0;
    for (int k = 1; k <= l / 2; ++k)
        ratio *= double(l / 2 + k) / (4.0 * double(k));
    const double sign = ((l / 2 - 1) % 2 == 0) ? 1.0 : -1.0;
    return 2.0 * std::numbers::pi * sign / (double(l + 2) * double(l - 1)) * ratio;
}

void clampedCosineTransfer(int order, const glm::dvec3& normal, double* out) {
    assert(order >= 1 && order <= sh::kMaxOrder);
    sh::evaluate(order, glm::normalize(normal), out);
    for (int l = 0; l < order; ++l) {
        const double weight = lambertWeight(l);
        for (int m = -l; m <= l; ++m)
            out[sh::index(l, m)] *= weight;
    }
}

} // namespace meadow::transfer
