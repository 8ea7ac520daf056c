// Real spherical harmonics (docs/ARCHITECTURE.md, Light transfer; Sloan, Kautz and Snyder 2002;
// Ramamoorthi and Hanrahan 2001). One convention for the whole of meadow, the shaders included:
//
//   - order n means bands l = 0 .. n-1, n^2 coefficients; index(l, m) = l (l + 1) + m.
//   - the polar axis is world +y (up), so functions that depend only on elevation (a uniform
//     overcast sky, the ground) live in the m = 0 coefficients; the azimuth is measured from
//     world +z towards world +x. In Cartesian form that is the textbook basis evaluated at
//     (X, Y, Z) = (dir.z, dir.x, dir.y), a proper rotation of the world axes.
//   - no Condon–Shortley phase: for order 3,
//       Y00 = 0.282095
//       Y1-1 = 0.488603 x        Y10 = 0.488603 y        Y11 = 0.488603 z
//       Y2-2 = 1.092548 x z      Y2-1 = 1.092548 x y     Y20 = 0.315392 (3 y^2 - 1)
//       Y21 = 1.092548 y z       Y22 = 0.546274 (z^2 - x^2)
//     with (x, y, z) the world direction.
//
// Coefficient vectors are std::vector<double> (one channel) or std::vector<glm::dvec3> (linear
// RGB), coefficientCount(order) long, indexed by index(l, m). A function f is represented by
// c_lm = ∫ f(ω) Y_lm(ω) dω over the sphere, and reconstructed as f(ω) ≈ Σ c_lm Y_lm(ω).
//
// Every function here and in light/sh.h takes the order as a parameter, 1 <= order <= kMaxOrder (asserted), and
// spans of exactly coefficientCount(order) coefficients (asserted): these are programmer errors,
// not input errors. Callers own every returned vector.
#pragma once

#include <glm/glm.hpp>

namespace meadow::sh {

inline constexpr int kDefaultOrder = 3;
inline constexpr int kMaxOrder = 8;

constexpr int coefficientCount(int order) {
    return order * order;
}
constexpr int index(int l, int m) {
    return l * (l + 1) + m;
}

// Writes the coefficientCount(order) basis functions at the unit direction `dir` into `out`.
// Precondition: 1 <= order <= kMaxOrder, |dir| = 1.
void evaluate(int order, const glm::dvec3& dir, double* out);

} // namespace meadow::sh
