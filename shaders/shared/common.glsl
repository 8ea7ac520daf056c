// GLSL-only helpers shared by meadow's shaders.
#ifndef MEADOW_COMMON_GLSL
#define MEADOW_COMMON_GLSL

#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"

#define MEADOW_FRAME_BLOCK(setIndex, bindingIndex)                   \
    layout(set = setIndex, binding = bindingIndex, std140) uniform FrameBlock { \
        GpuFrame frame;                                             \
    };

const float kPi = 3.14159265358979;

// The LOD view's colours (--debug-lod; instance.frag, far_splat.comp): LODs 0 to 4, red to purple,
// then the far field (kLodFar, lod_select.h), cyan. tests/support/far_compare.cpp tells them apart.
const vec3 kLodViewColors[6] = vec3[6](vec3(0.9, 0.15, 0.1), vec3(0.95, 0.75, 0.1), vec3(0.2, 0.8, 0.2),
                                       vec3(0.1, 0.6, 0.95), vec3(0.7, 0.3, 0.9), vec3(0.05, 0.9, 0.85));

// instance.vert to instance.frag, the flat word of a clump draw's facts (the w of its flat uvec4,
// whose xyz carry the constant albedo's float bits): lavapipe sets up every varying slot of every
// triangle on its one front-end thread, so the facts share one slot.
const uint kClumpDitherLevelMask = 31u;       // bits 0-4: the crossfade's dither level (lod_select.h)
const uint kClumpFadeLodBit = 1u << 5u;       // this draw is the instance's fadeLod
const uint kClumpFadingBit = 1u << 6u;        // the instance is crossfading (its fade above 0)
const uint kClumpConstantAlbedoBit = 1u << 7u; // xyz's albedo instead of the atlas
const uint kClumpLodShift = 8u;               // bits 8-10: the LOD the debug view shows

// Unshadowed irradiance on a surface of unit normal n from RGB sky SH of order 3 (sh[3 i + c],
// light/sh.h's basis: polar axis +y, azimuth from +z towards +x): the clamped cosine's zonal
// coefficients pi, 2 pi / 3, pi / 4 times the basis at n (Ramamoorthi and Hanrahan 2001).
// `sky(i)` must be a macro or function returning coefficient i's RGB.
#define MEADOW_SH_IRRADIANCE(result, sky, n)                                                         \
    {                                                                                                \
        vec3 nn = (n);                                                                               \
        float y[9];                                                                                  \
        y[0] = 0.282095;                                                                             \
        y[1] = 0.488603 * nn.x;                                                                      \
        y[2] = 0.488603 * nn.y;                                                                      \
        y[3] = 0.488603 * nn.z;                                                                      \
        y[4] = 1.092548 * nn.x * nn.z;                                                               \
        y[5] = 1.092548 * nn.x * nn.y;                                                               \
        y[6] = 0.315392 * (3.0 * nn.y * nn.y - 1.0);                                                 \
        y[7] = 1.092548 * nn.y * nn.z;                                                               \
        y[8] = 0.546274 * (nn.z * nn.z - nn.x * nn.x);                                               \
        const float band[9] = float[9](kPi, 2.0 * kPi / 3.0, 2.0 * kPi / 3.0, 2.0 * kPi / 3.0, kPi / 4.0, \
                                       kPi / 4.0, kPi / 4.0, kPi / 4.0, kPi / 4.0);                    \
        result = vec3(0.0);                                                                          \
        for (int i = 0; i < 9; ++i)                                                                  \
            result += band[i] * y[i] * sky(i);                                                       \
    }

#endif
