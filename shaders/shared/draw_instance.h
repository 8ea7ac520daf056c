// What the vertex shader needs of one visible instance, computed once per instance by the cull
// pass (and by the CPU-driven path) instead of once per vertex: lavapipe shades vertices on one
// thread, where every load counts. One function body, compiled as C++ and as GLSL.
//
// Usage from GLSL: include after common.glsl; from C++: include after gpu_types.h and
// motion_step.h (GpuMotionState).
#ifndef MEADOW_DRAW_INSTANCE_H
#define MEADOW_DRAW_INSTANCE_H

#ifdef __cplusplus
#include "gpu_types.h"
#include <algorithm>
#include <cmath>
namespace meadow::gpu {
#define MEADOW_DI_FN inline
#define MEADOW_DI_COS std::cos
#define MEADOW_DI_SIN std::sin
#define MEADOW_DI_FLOOR std::floor
#define MEADOW_DI_ABS std::fabs
#define MEADOW_DI_CLAMP(x, lo, hi) std::clamp(x, lo, hi)
#else
#define MEADOW_DI_FN
#define MEADOW_DI_COS cos
#define MEADOW_DI_SIN sin
#define MEADOW_DI_FLOOR floor
#define MEADOW_DI_ABS abs
#define MEADOW_DI_CLAMP(x, lo, hi) clamp(x, lo, hi)
#endif

// One visible instance, indexed like the instances (std430, 48 bytes).
struct GpuDrawInstance {
    vec4 positionScale; // as GpuInstance: xyz base, w scale (negative: mirrored)
    vec4 pose;          // x cos yaw, y sin yaw, z the old path's blend weight (0: no blend), w crossfade
                        // share (lod_select.h; 0: none)
    uvec4 offsets;      // x first coordinate of the frame's q (add the vertex's), y the old path's; z first
                        // uvec4 of its light variant (add the vertex's index times w's low 16 bits); w low
                        // 16 bits the light stride per clump vertex, high 16 bits the clump
};

// The instance's light variant (light.comp): its yaw bin, then the mirrored ones after the
// unmirrored.
MEADOW_DI_FN uint lightVariant(GpuInstance inst, GpuClump clump) {
    uint bins = clump.light.y;
    int bin = MEADOW_DI_CLAMP(int(MEADOW_DI_FLOOR((inst.yaw - clump.yawBins.x) * clump.yawBins.y)), 0, int(bins) - 1);
    return uint(bin) + (inst.positionScale.w < 0.0f ? bins : 0u);
}

MEADOW_DI_FN GpuDrawInstance makeDrawInstance(GpuInstance inst, GpuClump clump, GpuMotionState state, float lodX,
                                              bool lodChoice) {
    GpuDrawInstance d;
    d.positionScale = inst.positionScale;
    float blend = 0.0f;
    if (state.blendFramesLeft > 0u)
        blend = float(state.blendFramesLeft) / float(clump.graphSizes.z);
    d.pose =
        vec4(MEADOW_DI_COS(inst.yaw), MEADOW_DI_SIN(inst.yaw), blend, lodChoice ? lodX - MEADOW_DI_FLOOR(lodX) : 0.0f);
    uint bins = clump.light.y;
    uint variant = lightVariant(inst, clump);
    d.offsets =
        uvec4(clump.motion.y + state.frame * clump.motion.z, clump.motion.y + state.blendFrom * clump.motion.z,
              clump.light.x + variant * kLightVec4sPerVertex, (2u * bins * kLightVec4sPerVertex) | (inst.mesh << 16u));
    return d;
}

#ifdef __cplusplus
} // namespace meadow::gpu
#endif
#undef MEADOW_DI_FN
#undef MEADOW_DI_COS
#undef MEADOW_DI_SIN
#undef MEADOW_DI_FLOOR
#undef MEADOW_DI_ABS
#undef MEADOW_DI_CLAMP
#endif
