// GLSL-only helpers shared by meadow's shaders.
#ifndef MEADOW_COMMON_GLSL
#define MEADOW_COMMON_GLSL

#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"

#define MEADOW_FRAME_BLOCK(setIndex, bindingIndex)                   \
    layout(set = setIndex, binding = bindingIndex, std140) uniform FrameBlock { \
        GpuFrame frame;                                             \
    };

// Radiance of the analytic test sky in direction `dir` (unit, world, y up): a zenith-to-horizon
// gradient plus a soft sun disc. Linear units; tonemapped at the end of the frame.
vec3 skyRadiance(GpuFrame f, vec3 dir) {
    float up = clamp(dir.y, 0.0, 1.0);
    vec3 sky = mix(f.skyHorizon.rgb, f.skyZenith.rgb, sqrt(up));
    float sunCos = max(dot(dir, f.sunDirection.xyz), 0.0);
    sky += f.sunColor.rgb * f.sunDirection.w * (pow(sunCos, 2000.0) * 40.0 + pow(sunCos, 32.0) * 0.15);
    return dir.y < 0.0 ? f.skyHorizon.rgb * 0.5 : sky;
}

// Diffuse lighting: sun (Lambert, no shadows yet) plus a hemispherical sky term.
vec3 diffuseLight(GpuFrame f, vec3 normal) {
    float sun = max(dot(normal, f.sunDirection.xyz), 0.0) * f.sunDirection.w;
    float hemi = 0.5 + 0.5 * normal.y;
    vec3 ambient = mix(f.skyHorizon.rgb * 0.6, f.skyZenith.rgb, hemi);
    return f.sunColor.rgb * sun + ambient;
}

#endif
