// The wind over the field at run time (docs/ARCHITECTURE.md, The run time): a wind level at every
// point and motion tick, which the animate pass turns into each instance's target level for its
// motion-graph step. One function body, compiled as C++ for the CPU reference and as GLSL for
// animate.comp, so the two agree bit for bit.
//
// Like the paper's wind generator, the level is a base level plus waves that travel across the
// field along the wind and gusts: here, a smooth periodic wave (amplitude, wavelength, speed) and
// value noise on a lattice of gust cells that drifts downwind. Only IEEE-exact operations are
// used (add, multiply, floor, comparisons; no sin, exp or division), `precise` in GLSL and
// -ffp-contract=off in C++, so both sides round identically; time enters as an integer tick.
//
// Usage from C++:   float level = gpu::windLevelAt(frame, x, z, tick);
// Usage from GLSL:  #include "wind_field.h" after gpu_types.h; windLevelAt(frame, x, z, tick).
#ifndef MEADOW_WIND_FIELD_H
#define MEADOW_WIND_FIELD_H

#ifdef __cplusplus
#include "gpu_types.h"
#include "motion_step.h"
#include <cmath>
namespace meadow::gpu {
#define MEADOW_WIND_FN inline
#define MEADOW_WIND_PRECISE
#define MEADOW_WIND_FLOOR std::floor
#define MEADOW_WIND_ABS std::fabs
#define MEADOW_WIND_FRAME const GpuFrame&
#define MEADOW_WIND_FLOAT(x) static_cast<float>(x)
#define MEADOW_WIND_INT(x) static_cast<int>(x)
#define MEADOW_WIND_UINT(x) static_cast<uint>(x)
#else
#define MEADOW_WIND_FN
#define MEADOW_WIND_PRECISE precise
#define MEADOW_WIND_FLOOR floor
#define MEADOW_WIND_ABS abs
#define MEADOW_WIND_FRAME GpuFrame
#define MEADOW_WIND_FLOAT(x) float(x)
#define MEADOW_WIND_INT(x) int(x)
#define MEADOW_WIND_UINT(x) uint(x)
#endif

// A smooth bump of period 1: 1 at integers, -1 half-way, smoothstep-shaped in between (C1).
MEADOW_WIND_FN float windWaveShape(float phase) {
    MEADOW_WIND_PRECISE float t = phase - MEADOW_WIND_FLOOR(phase);
    MEADOW_WIND_PRECISE float tri = MEADOW_WIND_ABS(t * 2.0f - 1.0f);
    MEADOW_WIND_PRECISE float eased = tri * tri * (3.0f - tri * 2.0f);
    return eased * 2.0f - 1.0f;
}

// Value noise in [0, 1] at a lattice point, from the motion step's PCG hash.
MEADOW_WIND_FN float windLatticeValue(int i, int j) {
    uint h = motionPcgHash(MEADOW_WIND_UINT(i) * 73856093u ^ motionPcgHash(MEADOW_WIND_UINT(j) + 19349663u));
    return MEADOW_WIND_FLOAT(h >> 8u) * (1.0f / 16777216.0f);
}

// Bilinear value noise with smoothstep weights, in [0, 1].
MEADOW_WIND_FN float windValueNoise(float u, float v) {
    MEADOW_WIND_PRECISE float fu = MEADOW_WIND_FLOOR(u), fv = MEADOW_WIND_FLOOR(v);
    int i = MEADOW_WIND_INT(fu), j = MEADOW_WIND_INT(fv);
    MEADOW_WIND_PRECISE float a = u - fu, b = v - fv;
    MEADOW_WIND_PRECISE float wa = a * a * (3.0f - a * 2.0f), wb = b * b * (3.0f - b * 2.0f);
    MEADOW_WIND_PRECISE float v00 = windLatticeValue(i, j), v10 = windLatticeValue(i + 1, j);
    MEADOW_WIND_PRECISE float v01 = windLatticeValue(i, j + 1), v11 = windLatticeValue(i + 1, j + 1);
    MEADOW_WIND_PRECISE float low = v00 + (v10 - v00) * wa;
    MEADOW_WIND_PRECISE float high = v01 + (v11 - v01) * wa;
    return low + (high - low) * wb;
}

// The wind level (continuous; the motion graph's levels are its integers) at world (x, z) at a
// motion tick. Ticks are taken modulo 2^20 (9.7 hours at 30 Hz) to keep float(tick) exact.
MEADOW_WIND_FN float windLevelAt(MEADOW_WIND_FRAME f, float x, float z, uint tick) {
    MEADOW_WIND_PRECISE float ticks = MEADOW_WIND_FLOAT(tick & 0xfffffu);
    MEADOW_WIND_PRECISE float along = x * f.windWave.x + z * f.windWave.y;
    MEADOW_WIND_PRECISE float across = z * f.windWave.x - x * f.windWave.y;
    MEADOW_WIND_PRECISE float phase = along * f.windShape.x - ticks * f.windShape.y;
    MEADOW_WIND_PRECISE float wave = windWaveShape(phase) * f.windWave.w;
    MEADOW_WIND_PRECISE float gustU = along * f.windShape.w - ticks * f.windGust.x;
    MEADOW_WIND_PRECISE float gustV = across * f.windShape.w;
    MEADOW_WIND_PRECISE float gust = windValueNoise(gustU, gustV) * f.windShape.z;
    return f.windWave.z + wave + gust;
}

// The motion graph level to head for: the wind level rounded down, within [0, levelCount - 1].
MEADOW_WIND_FN uint windTargetLevel(float level, uint levelCount) {
    if (!(level > 0.0f))
        return 0u;
    MEADOW_WIND_PRECISE float top = MEADOW_WIND_FLOAT(levelCount - 1u);
    return level >= top ? levelCount - 1u : MEADOW_WIND_UINT(level);
}

#ifdef __cplusplus
} // namespace meadow::gpu
#endif
#undef MEADOW_WIND_FN
#undef MEADOW_WIND_PRECISE
#undef MEADOW_WIND_FLOOR
#undef MEADOW_WIND_ABS
#undef MEADOW_WIND_FRAME
#undef MEADOW_WIND_FLOAT
#undef MEADOW_WIND_INT
#undef MEADOW_WIND_UINT
#endif
