// The sky's SH radiance carried into a placed clump's own frame (docs/ARCHITECTURE.md, Light
// transfer), one function body compiled as C++ (tests, CPU references) and as GLSL (compute
// passes), like motion_step.h.
//
// Why: a clump's radiance transfer is baked once in the clump's frame, but each instance stands
// at its own yaw and may be mirrored, so the sky must be expressed in that frame before the dot
// product with the transfer vector: L_clump(ω) = L_world(A ω). Instances are placed by
// world = position + R(yaw) M p, with R(yaw) the turn about +y that takes the azimuth
// φ = atan2(x, z) to φ + yaw, and M (mirrored instances only) the reflection about the vertical
// plane through the wind direction (wx, 0, wz), φ -> 2 α - φ with α = atan2(wx, wz). So A = R M
// maps φ -> s φ + δ: s = -1, δ = 2 α + yaw when mirrored; s = +1, δ = yaw otherwise.
//
// Both keep the polar axis (+y), so the m = 0 coefficients are unchanged, and in sh.h's basis
// (index(l, m) multiplies cos(m φ), index(l, -m) multiplies sin(m φ), same normalisation) each
// band mixes only its ±m pairs; with a = c[index(l, m)], b = c[index(l, -m)], m > 0:
//   a' = a cos(m δ) + b sin(m δ)
//   b' = s (b cos(m δ) - a sin(m δ))
// That is a 2 x 2 turn per pair instead of the general Ivanic–Ruedenberg rotation of
// precompute/light/sh.h, and only one cos and one sin per instance (m = 2 by double angles).
//
// Order 3 only (bands 0..2), RGB laid out sh[3 i + c] (i coefficient index, c channel): 27 floats.
#ifndef MEADOW_SH_LIGHT_H
#define MEADOW_SH_LIGHT_H

#ifdef __cplusplus
#include <cmath>
#include <cstdint>
namespace meadow::gpu {
using uint = std::uint32_t;
#define MEADOW_SH_CONST inline constexpr uint
#define MEADOW_SH_FN inline
#define MEADOW_SH_IN_ARRAY(name, n) const float(&name)[n]
#define MEADOW_SH_OUT_ARRAY(name, n) float(&name)[n]
using std::cos;
using std::sin;
#else
#define MEADOW_SH_CONST const uint
#define MEADOW_SH_FN
#define MEADOW_SH_IN_ARRAY(name, n) in float name[n]
#define MEADOW_SH_OUT_ARRAY(name, n) out float name[n]
#endif

MEADOW_SH_CONST kShLightOrder = 3u;
MEADOW_SH_CONST kShLightCoefficients = 9u; // kShLightOrder^2
MEADOW_SH_CONST kShLightRgbFloats = 27u;   // 3 kShLightCoefficients

// s of A: -1 for a mirrored instance (the reflection reverses the azimuth), +1 otherwise.
MEADOW_SH_FN float shClumpFrameSign(bool mirrored) {
    return mirrored ? -1.0f : 1.0f;
}

// δ of A in radians. windAzimuth = atan2(wx, wz) of the wind direction the mirror plane contains;
// ignored when not mirrored.
MEADOW_SH_FN float shClumpFrameDelta(float yaw, bool mirrored, float windAzimuth) {
    return mirrored ? 2.0f * windAzimuth + yaw : yaw;
}

// skyOut = the coefficients of ω -> L(A ω) for skyIn those of L, with A given by s (+1 or -1) and
// δ (radians) as above. In C++ skyIn and skyOut may be the same array: each pair is read before
// it is written.
MEADOW_SH_FN void shSkyToClumpFrame(MEADOW_SH_IN_ARRAY(skyIn, kShLightRgbFloats), float s, float delta,
                                    MEADOW_SH_OUT_ARRAY(skyOut, kShLightRgbFloats)) {
    float c1 = cos(delta);
    float s1 = sin(delta);
    float c2 = c1 * c1 - s1 * s1; // cos 2δ
    float s2 = 2.0f * s1 * c1;    // sin 2δ
    for (uint c = 0u; c < 3u; ++c) {
        // Pairs (index(l, m), index(l, -m)): (3, 1) for l = 1; (7, 5) and (8, 4) for l = 2.
        float a11 = skyIn[3u * 3u + c], b11 = skyIn[3u * 1u + c];
        float a21 = skyIn[3u * 7u + c], b21 = skyIn[3u * 5u + c];
        float a22 = skyIn[3u * 8u + c], b22 = skyIn[3u * 4u + c];
        // m = 0: index 0, 2, 6.
        skyOut[3u * 0u + c] = skyIn[3u * 0u + c];
        skyOut[3u * 2u + c] = skyIn[3u * 2u + c];
        skyOut[3u * 6u + c] = skyIn[3u * 6u + c];
        skyOut[3u * 3u + c] = a11 * c1 + b11 * s1;
        skyOut[3u * 1u + c] = s * (b11 * c1 - a11 * s1);
        skyOut[3u * 7u + c] = a21 * c1 + b21 * s1;
        skyOut[3u * 5u + c] = s * (b21 * c1 - a21 * s1);
        skyOut[3u * 8u + c] = a22 * c2 + b22 * s2;
        skyOut[3u * 4u + c] = s * (b22 * c2 - a22 * s2);
    }
}

#ifdef __cplusplus
static_assert(kShLightCoefficients == kShLightOrder * kShLightOrder, "order 3 has 9 coefficients");
static_assert(kShLightRgbFloats == 3u * kShLightCoefficients, "RGB: three floats per coefficient");
} // namespace meadow::gpu
#endif
#undef MEADOW_SH_CONST
#undef MEADOW_SH_FN
#undef MEADOW_SH_IN_ARRAY
#undef MEADOW_SH_OUT_ARRAY
#endif
