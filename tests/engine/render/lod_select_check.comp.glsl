#version 460
// Build-time check that shaders/shared/lod_select.h compiles as GLSL (the cull pass will include
// it): one LOD choice per invocation. Not a render pass.
#extension GL_GOOGLE_include_directive : require
#include "lod_select.h"

layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer Radii { vec2 radiusAndRandom[]; };
layout(std430, set = 0, binding = 1) buffer States { float x[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Choices { GpuLodChoice choices[]; };
layout(std140, set = 0, binding = 3) uniform Params { GpuLodParams params; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= x.length())
        return;
    GpuLodChoice c = lodSelect(params, radiusAndRandom[i].x, radiusAndRandom[i].y, x[i]);
    x[i] = c.x;
    if (!lodDitherKeeps(c.fadeLod != c.lod, c.fade, i, i / 64u))
        c.fade = -1.0;
    choices[i] = c;
}
