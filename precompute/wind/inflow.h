// The ambient wind that enters the solver box: a mean power-law profile, low-frequency gusts and
// a frozen field of synthetic turbulence carried along at the mean speed (Taylor's hypothesis).
// The solver prescribes it on the upwind faces, samples it wherever a semi-Lagrangian backtrace
// leaves the box, and returns it for points outside the box.
//
//   u_amb(p, t) = U(z) * g(xi, t) * (d + c_t * I * T(p - U_ref * d * t))
//
//   z      height above the ground (m); U(z) = U_ref * (max(z, z_min) / 1 m)^(1/7), the classic
//          one-seventh power law of a neutral surface layer; z_min = 1 cm keeps it finite.
//   d      the level's unit direction; U_ref its meanSpeed; I its turbulence.
//   g      gust factor 1 + I * c_g * sum_i a_i sin(2 pi f_i s + phi_i), s = t - xi / U_ref, with
//          xi the distance along d from the box centre: gust fronts travel with the mean wind.
//          Three seeded partials near 1 / gustPeriod; floored at 0.1 so a gust never reverses the
//          wind.
//   T      a periodic, divergence-free tile of random Fourier modes with a Kolmogorov-like
//          spectrum (E(k) ~ k^(-5/3)), unit RMS per component (Stam & Fiume 1993 synthesise
//          turbulent wind the same way). Wavelengths span 6 cells to the tile period.
//   c_g, c_t  split the variance: c_g = 0.6, c_t = 0.8 (0.6^2 + 0.8^2 = 1), so the streamwise
//          std / mean of the ambient wind is about I.
//
// All randomness comes from meadow::Random seeded with WindLevelParams::seed.
#pragma once

#include "wind_params.h"

#include <array>
#include <vector>

namespace meadow {

class InflowField {
  public:
    InflowField(const FluidGrid& grid, const WindLevelParams& level);

    // Exact (analytic) ambient velocity, m/s. Any p, any t.
    glm::vec3 velocity(glm::vec3 p, double t) const;
    // Mean profile U(z), m/s, z the height above the ground in m.
    float profileSpeed(float height) const;
    float gustFactor(float streamwise, double t) const;
    // The turbulence tile at a point of the moving frame (dimensionless, unit RMS per component).
    glm::vec3 tileSample(glm::vec3 p, double t) const;

    // Fast path for the solver's inner loops: fills the per-step gust table for time t. Afterwards
    // fastVelocity() agrees with velocity(p, t) to about 1e-3 of the gust amplitude (linear
    // interpolation of the gust factor along xi and of the profile over height).
    void prepare(double t);
    glm::vec3 fastVelocity(glm::vec3 p) const;

    const glm::vec3& direction() const { return direction_; }

  private:
    static constexpr int kTileSize = 32; // power of two: wrapping is a mask
    static constexpr int kGustPartials = 3;

    glm::vec3 tileAt(glm::vec3 tileCoord) const;

    FluidGrid grid_;
    glm::vec3 direction_;
    float meanSpeed_;
    float turbulence_;
    glm::vec3 centre_;
    float tileSpacing_;
    std::vector<glm::vec4> tile_; // kTileSize^3, w unused (one SSE register per sample)
    std::array<float, kGustPartials> gustAmplitude_{};
    std::array<float, kGustPartials> gustFrequency_{}; // Hz
    std::array<float, kGustPartials> gustPhase_{};
    // Tables: profile over height (8 samples per cell), gust over xi for the prepared time.
    float profileStep_ = 0.0f;
    std::vector<float> profileTable_;
    float gustStep_ = 0.0f;
    float gustXiMin_ = 0.0f;
    std::vector<float> gustTable_;
    glm::vec3 tileShift_{0.0f}; // U_ref * d * t wrapped to the tile period, for the prepared time
};

} // namespace meadow
