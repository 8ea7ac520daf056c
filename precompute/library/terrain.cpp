#include "library/terrain.h"

#include "core/error.h"
#include "core/random.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <string>

namespace meadow {
namespace {

// 2D gradient noise takes values in [-sqrt(1/2), sqrt(1/2)] with unit gradients.
constexpr double kNoiseBound = 0.70710678118654752;

// The unit gradient at lattice point (i, j) of octave `octave`: a hashed angle.
glm::dvec2 latticeGradient(int64_t i, int64_t j, uint32_t octave, uint64_t seed) {
    uint64_t h = splitMix64(seed ^ 0x7465727261696eull); // "terrain"
    h = splitMix64(h ^ uint64_t(octave));
    h = splitMix64(h ^ uint64_t(i));
    h = splitMix64(h ^ uint64_t(j));
    const double angle = double(h >> 11) * (glm::two_pi<double>() / 9007199254740992.0); // 53 bits
    return {std::cos(angle), std::sin(angle)};
}

// Perlin gradient noise at (x, z) in lattice units: value, d/dx, d/dz. Quintic fade
// 6t^5 - 15t^4 + 10t^3 (Perlin 2002).
glm::dvec3 gradientNoise(double x, double z, uint32_t octave, uint64_t seed) {
    const double fx = std::floor(x), fz = std::floor(z);
    const int64_t i = int64_t(fx), j = int64_t(fz);
    const double tx = x - fx, tz = z - fz;
    const glm::dvec2 g00 = latticeGradient(i, j, octave, seed), g10 = latticeGradient(i + 1, j, octave, seed);
    const glm::dvec2 g01 = latticeGradient(i, j + 1, octave, seed), g11 = latticeGradient(i + 1, j + 1, octave, seed);
    const double v00 = g00.x * tx + g00.y * tz, v10 = g10.x * (tx - 1.0) + g10.y * tz;
    const double v01 = g01.x * tx + g01.y * (tz - 1.0), v11 = g11.x * (tx - 1.0) + g11.y * (tz - 1.0);
    const double u = tx * tx * tx * (tx * (tx * 6.0 - 15.0) + 10.0);
    const double w = tz * tz * tz * (tz * (tz * 6.0 - 15.0) + 10.0);
    const double du = 30.0 * tx * tx * (tx - 1.0) * (tx - 1.0);
    const double dw = 30.0 * tz * tz * (tz - 1.0) * (tz - 1.0);
    const double k = v00 - v10 - v01 + v11;
    const double value = v00 + u * (v10 - v00) + w * (v01 - v00) + u * w * k;
    // d/dx of the corner values is the gradients' x; of the fades, du and dw.
    const double dx = g00.x + u * (g10.x - g00.x) + w * (g01.x - g00.x) + u * w * (g00.x - g10.x - g01.x + g11.x) +
                      du * ((v10 - v00) + w * k);
    const double dz = g00.y + u * (g10.y - g00.y) + w * (g01.y - g00.y) + u * w * (g00.y - g10.y - g01.y + g11.y) +
                      dw * ((v01 - v00) + u * k);
    return {value, dx, dz};
}

} // namespace

Terrain::Terrain(const TerrainParams& params) : params_(params) {
    if (!std::isfinite(params.amplitude) || params.amplitude < 0.0f)
        throw Error("terrain: amplitude " + std::to_string(params.amplitude) + " m is not a finite number >= 0");
    if (!std::isfinite(params.wavelength) || !(params.wavelength > 0.0f))
        throw Error("terrain: wavelength " + std::to_string(params.wavelength) + " m is not a positive finite number");
    if (params.octaves < 1 || params.octaves > 12)
        throw Error("terrain: " + std::to_string(params.octaves) + " octaves is outside 1 .. 12");
    double weights = 0.0;
    for (uint32_t o = 0; o < params.octaves; ++o)
        weights += std::ldexp(1.0, -int(o));
    scale_ = double(params.amplitude) / (weights * kNoiseBound);
}

glm::dvec3 Terrain::evaluate(double x, double z) const {
    glm::dvec3 sum(0.0);
    for (uint32_t o = 0; o < params_.octaves; ++o) {
        const double frequency = std::ldexp(1.0, int(o)) / double(params_.wavelength); // lattice cells per m
        const glm::dvec3 n = gradientNoise(x * frequency, z * frequency, o, params_.seed);
        const double weight = std::ldexp(1.0, -int(o));
        sum += weight * glm::dvec3(n.x, n.y * frequency, n.z * frequency);
    }
    return sum * scale_;
}

float Terrain::height(float x, float z) const {
    return float(evaluate(double(x), double(z)).x);
}

glm::vec2 Terrain::gradient(float x, float z) const {
    const glm::dvec3 e = evaluate(double(x), double(z));
    return {float(e.y), float(e.z)};
}

glm::vec3 Terrain::normal(float x, float z) const {
    const glm::dvec3 e = evaluate(double(x), double(z));
    return glm::vec3(glm::normalize(glm::dvec3(-e.y, 1.0, -e.z)));
}

Mesh makeTerrainMesh(const TerrainParams& params, glm::vec2 fieldHalfExtent, float margin, float spacing) {
    const Terrain terrain(params);
    const float plain = -params.amplitude - 0.05f;
    const glm::vec2 half = fieldHalfExtent + glm::vec2(margin);
    const uint32_t nx = uint32_t(std::ceil(2.0f * half.x / spacing)) + 1;
    const uint32_t nz = uint32_t(std::ceil(2.0f * half.y / spacing)) + 1;
    auto heightAt = [&](float x, float z) {
        const float outside = std::max({std::abs(x) - fieldHalfExtent.x, std::abs(z) - fieldHalfExtent.y, 0.0f});
        const float t = margin > 0.0f ? std::clamp(outside / margin, 0.0f, 1.0f) : (outside > 0.0f ? 1.0f : 0.0f);
        const float ease = 1.0f - t * t * (3.0f - 2.0f * t);
        return plain + (terrain.height(x, z) - plain) * ease;
    };
    Mesh mesh;
    std::vector<float> heights(size_t(nx) * nz);
    for (uint32_t j = 0; j < nz; ++j)
        for (uint32_t i = 0; i < nx; ++i) {
            const float x = -half.x + 2.0f * half.x * float(i) / float(nx - 1);
            const float z = -half.y + 2.0f * half.y * float(j) / float(nz - 1);
            heights[size_t(j) * nx + i] = heightAt(x, z);
        }
    const float dx = 2.0f * half.x / float(nx - 1), dz = 2.0f * half.y / float(nz - 1);
    for (uint32_t j = 0; j < nz; ++j)
        for (uint32_t i = 0; i < nx; ++i) {
            const float x = -half.x + dx * float(i), z = -half.y + dz * float(j);
            auto h = [&](uint32_t a, uint32_t b) { return heights[size_t(b) * nx + a]; };
            const float gx = (h(std::min(i + 1, nx - 1), j) - h(i > 0 ? i - 1 : 0, j)) /
                             (dx * float(std::min(i + 1, nx - 1) - (i > 0 ? i - 1 : 0)));
            const float gz = (h(i, std::min(j + 1, nz - 1)) - h(i, j > 0 ? j - 1 : 0)) /
                             (dz * float(std::min(j + 1, nz - 1) - (j > 0 ? j - 1 : 0)));
            mesh.vertices.push_back({glm::vec4(x, heights[size_t(j) * nx + i], z, 0.0f),
                                     glm::vec4(glm::normalize(glm::vec3(-gx, 1.0f, -gz)), 0.0f)});
        }
    for (uint32_t j = 0; j + 1 < nz; ++j)
        for (uint32_t i = 0; i + 1 < nx; ++i) {
            const uint32_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
        }
    // The plain: a ring from the grid's border out to 1 km, at the border's height.
    const uint32_t ring = uint32_t(mesh.vertices.size());
    const float far = 1000.0f;
    const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const glm::vec2& c : corners)
        mesh.vertices.push_back({glm::vec4(c.x * half.x, plain, c.y * half.y, 0.0f), glm::vec4(0, 1, 0, 0)});
    for (const glm::vec2& c : corners)
        mesh.vertices.push_back(
            {glm::vec4(c.x * (half.x + far), plain, c.y * (half.y + far), 0.0f), glm::vec4(0, 1, 0, 0)});
    for (uint32_t k = 0; k < 4; ++k) {
        const uint32_t in0 = ring + k, in1 = ring + (k + 1) % 4, out0 = ring + 4 + k, out1 = ring + 4 + (k + 1) % 4;
        mesh.indices.insert(mesh.indices.end(), {in0, out0, in1, in1, out0, out1});
    }
    return mesh;
}

} // namespace meadow
