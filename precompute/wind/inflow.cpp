// Ambient wind: profile, gusts and a synthetic turbulence tile (see inflow.h).
#include "inflow.h"

#include "core/random.h"
#include "float4.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace meadow {

namespace {

constexpr float kProfileExponent = 1.0f / 7.0f; // neutral surface layer power law
constexpr float kProfileMinHeight = 0.01f;      // m
constexpr float kGustShare = 0.6f;              // c_g
constexpr float kTurbulenceShare = 0.8f;        // c_t
constexpr float kGustFloor = 0.1f;
constexpr int kTurbulenceModes = 64;
constexpr float kShortestWavelengthCells = 6.0f; // grid cells; shorter eddies die in the solver anyway
constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

glm::vec3 horizontalUnit(glm::vec3 direction) {
    glm::vec3 d{direction.x, 0.0f, direction.z};
    float length = glm::length(d);
    return length > 0.0f ? d / length : glm::vec3{1.0f, 0.0f, 0.0f};
}

} // namespace

InflowField::InflowField(const FluidGrid& grid, const WindLevelParams& level)
    : grid_(grid), direction_(horizontalUnit(level.direction)), meanSpeed_(std::max(level.meanSpeed, 0.0f)),
      turbulence_(std::max(level.turbulence, 0.0f)) {
    glm::vec3 extent = glm::vec3(grid.cells) * grid.cellSize;
    centre_ = grid.origin + 0.5f * extent;
    Random random(splitMix64(level.seed ^ 0x77696e64ull)); // "wind"

    // Gusts: a dominant partial at 1 / gustPeriod, a slower and a faster one, seeded. Amplitudes
    // are normalised so that the sum has standard deviation 1 (each sine has variance a^2 / 2).
    float period = std::max(level.gustPeriod, 1e-3f);
    const float relativeFrequency[kGustPartials] = {1.0f, random.uniform(0.35f, 0.6f), random.uniform(1.8f, 2.6f)};
    const float weight[kGustPartials] = {0.7f, 0.5f, 0.3f};
    float variance = 0.0f;
    for (int i = 0; i < kGustPartials; ++i) {
        variance += 0.5f * weight[i] * weight[i];
    }
    for (int i = 0; i < kGustPartials; ++i) {
        gustAmplitude_[i] = weight[i] / std::sqrt(variance);
        gustFrequency_[i] = relativeFrequency[i] / period;
        gustPhase_[i] = random.uniform(0.0f, kTwoPi);
    }

    // Turbulence tile: integer wave vectors n (so the tile is periodic), |n| log-uniform between 1
    // and the shortest wavelength, amplitude vector perpendicular to n (divergence-free). With
    // log-uniform |k| the mode density per dk is ~1/k, so energy per mode ~ E(k) k = k^(-2/3) gives
    // the k^(-5/3) spectrum: amplitude ~ k^(-1/3).
    tileSpacing_ = 1.5f * grid.cellSize;
    const float maxWaveNumber = kTileSize * 1.5f / kShortestWavelengthCells; // in units of 2 pi / period
    tile_.assign(static_cast<size_t>(kTileSize) * kTileSize * kTileSize, glm::vec4(0.0f));
    std::array<float, kTileSize> cosTable{};
    for (int mode = 0; mode < kTurbulenceModes; ++mode) {
        glm::ivec3 n{0};
        float radius = 1.0f;
        while (n == glm::ivec3(0)) {
            radius = std::exp(random.uniform(0.0f, std::log(maxWaveNumber)));
            float cosTheta = random.uniform(-1.0f, 1.0f);
            float phi = random.uniform(0.0f, kTwoPi);
            float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
            glm::vec3 unit{sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi)};
            n = glm::ivec3(glm::round(unit * radius));
        }
        glm::vec3 k = glm::normalize(glm::vec3(n));
        glm::vec3 amplitude{0.0f};
        while (glm::length(amplitude) < 1e-3f) {
            glm::vec3 e{random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f), random.uniform(-1.0f, 1.0f)};
            amplitude = e - glm::dot(e, k) * k;
        }
        amplitude = glm::normalize(amplitude) * std::pow(glm::length(glm::vec3(n)), -1.0f / 3.0f);
        float phase = random.uniform(0.0f, kTwoPi);
        // n . (i, j, k) is an integer, so the mode takes only kTileSize distinct values.
        for (int m = 0; m < kTileSize; ++m) {
            cosTable[m] = std::cos(kTwoPi * static_cast<float>(m) / kTileSize + phase);
        }
        for (int z = 0; z < kTileSize; ++z) {
            for (int y = 0; y < kTileSize; ++y) {
                for (int x = 0; x < kTileSize; ++x) {
                    int m = (n.x * x + n.y * y + n.z * z) & (kTileSize - 1);
                    tile_[(static_cast<size_t>(z) * kTileSize + y) * kTileSize + x] +=
                        glm::vec4(amplitude * cosTable[m], 0.0f);
                }
            }
        }
    }
    double sumSquares = 0.0;
    for (const glm::vec4& value : tile_) {
        sumSquares += static_cast<double>(glm::dot(value, value));
    }
    float rms = static_cast<float>(std::sqrt(sumSquares / (3.0 * static_cast<double>(tile_.size()))));
    for (glm::vec4& value : tile_) {
        value /= rms;
    }

    // Profile table over the box height plus one cell, 8 samples per cell.
    profileStep_ = grid.cellSize / 8.0f;
    profileTable_.resize(static_cast<size_t>(grid.cells.y + 1) * 8 + 2);
    for (size_t i = 0; i < profileTable_.size(); ++i) {
        profileTable_[i] = profileSpeed(static_cast<float>(i) * profileStep_);
    }
    // Gust table over the box diagonal plus 2 m on each side (farther than any backtrace goes).
    gustStep_ = 0.5f * grid.cellSize;
    float halfSpan = 0.5f * glm::length(extent) + 2.0f;
    gustXiMin_ = -halfSpan;
    gustTable_.assign(static_cast<size_t>(std::ceil(2.0f * halfSpan / gustStep_)) + 2, 1.0f);
    prepare(0.0);
}

float InflowField::profileSpeed(float height) const {
    return meanSpeed_ * std::pow(std::max(height, kProfileMinHeight), kProfileExponent);
}

float InflowField::gustFactor(float streamwise, double t) const {
    double s = meanSpeed_ > 1e-6f ? t - static_cast<double>(streamwise) / meanSpeed_ : t;
    double sum = 0.0;
    for (int i = 0; i < kGustPartials; ++i) {
        double angle = 2.0 * std::numbers::pi * gustFrequency_[i] * s + gustPhase_[i];
        sum += gustAmplitude_[i] * std::sin(angle);
    }
    return std::max(kGustFloor, 1.0f + turbulence_ * kGustShare * static_cast<float>(sum));
}

glm::vec3 InflowField::tileAt(glm::vec3 c) const {
    glm::vec3 f = glm::floor(c);
    glm::vec3 t = c - f;
    glm::ivec3 i0 = glm::ivec3(f);
    constexpr int kMask = kTileSize - 1;
    auto at = [&](int x, int y, int z) {
        return load4(tile_[(static_cast<size_t>(z & kMask) * kTileSize + (y & kMask)) * kTileSize + (x & kMask)]);
    };
    Float4 c00 = at(i0.x, i0.y, i0.z) + t.x * (at(i0.x + 1, i0.y, i0.z) - at(i0.x, i0.y, i0.z));
    Float4 c10 = at(i0.x, i0.y + 1, i0.z) + t.x * (at(i0.x + 1, i0.y + 1, i0.z) - at(i0.x, i0.y + 1, i0.z));
    Float4 c01 = at(i0.x, i0.y, i0.z + 1) + t.x * (at(i0.x + 1, i0.y, i0.z + 1) - at(i0.x, i0.y, i0.z + 1));
    Float4 c11 = at(i0.x, i0.y + 1, i0.z + 1) + t.x * (at(i0.x + 1, i0.y + 1, i0.z + 1) - at(i0.x, i0.y + 1, i0.z + 1));
    Float4 y0 = c00 + t.y * (c10 - c00);
    Float4 y1 = c01 + t.y * (c11 - c01);
    Float4 r = y0 + t.z * (y1 - y0);
    return {r[0], r[1], r[2]};
}

namespace {
// The frozen field's displacement U_ref * d * t, wrapped to the tile period in double precision so
// that long runs (thousands of seconds) keep full float resolution inside the tile.
glm::vec3 wrappedShift(glm::vec3 direction, float meanSpeed, double t, double period) {
    glm::vec3 shift;
    for (int a = 0; a < 3; ++a) {
        double travelled = static_cast<double>(direction[a]) * meanSpeed * t;
        shift[a] = static_cast<float>(travelled - period * std::floor(travelled / period));
    }
    return shift;
}
} // namespace

glm::vec3 InflowField::tileSample(glm::vec3 p, double t) const {
    glm::vec3 shift = wrappedShift(direction_, meanSpeed_, t, static_cast<double>(tileSpacing_) * kTileSize);
    return tileAt((p - grid_.origin - shift) / tileSpacing_);
}

glm::vec3 InflowField::velocity(glm::vec3 p, double t) const {
    float speed = profileSpeed(p.y - grid_.origin.y) * gustFactor(glm::dot(p - centre_, direction_), t);
    return speed * (direction_ + (turbulence_ * kTurbulenceShare) * tileSample(p, t));
}

void InflowField::prepare(double t) {
    for (size_t i = 0; i < gustTable_.size(); ++i) {
        gustTable_[i] = gustFactor(gustXiMin_ + static_cast<float>(i) * gustStep_, t);
    }
    tileShift_ = wrappedShift(direction_, meanSpeed_, t, static_cast<double>(tileSpacing_) * kTileSize);
}

glm::vec3 InflowField::fastVelocity(glm::vec3 p) const {
    auto lerpTable = [](const std::vector<float>& table, float coordinate) {
        float c = std::clamp(coordinate, 0.0f, static_cast<float>(table.size() - 1) - 1e-3f);
        auto i = static_cast<size_t>(c);
        float t = c - static_cast<float>(i);
        return table[i] + t * (table[i + 1] - table[i]);
    };
    float profile = lerpTable(profileTable_, (p.y - grid_.origin.y) / profileStep_);
    float gust = lerpTable(gustTable_, (glm::dot(p - centre_, direction_) - gustXiMin_) / gustStep_);
    glm::vec3 turbulence = tileAt((p - grid_.origin - tileShift_) / tileSpacing_);
    return (profile * gust) * (direction_ + (turbulence_ * kTurbulenceShare) * turbulence);
}

} // namespace meadow
