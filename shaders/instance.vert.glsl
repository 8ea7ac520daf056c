#version 460
// Instanced plant meshes: vertices pulled from a storage buffer, instances addressed through the
// visible list that the cull pass compacted (this draw's range starts at its firstInstance,
// which gl_InstanceIndex includes).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "lod_select.h"

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer VisibleList { uint visible[]; };
layout(set = 0, binding = 3, std430) readonly buffer Vertices { GpuVertex vertices[]; };
// xz: the unit normal of the vertical plane that holds the wind direction the clumps were
// simulated in. A mirrored instance (negative scale) reflects about it before its yaw, so it
// still sways downwind (placement/instance.h).
layout(push_constant) uniform InstanceParams { vec4 mirrorNormal; };
// Binding 4, before the fragment stage's atlas at 5: with the atlas between this stage's storage
// buffers (LodState at 5), lavapipe (Mesa 22.3) at 128-bit vectors corrupted its heap.
layout(set = 0, binding = 4, std430) readonly buffer LodState { float lodX[]; };

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec2 outUv;
layout(location = 2) out float outTint;
layout(location = 3) out float outHeight;
// The crossfade (lod_select.h): this draw's share and whether it is the instance's fadeLod.
layout(location = 4) flat out float outFade;
layout(location = 5) flat out uint outIsFadeLod;

void main() {
    uint entry = visible[gl_InstanceIndex];
    uint index = entry & ~kLodFadeEntryBit;
    GpuInstance inst = instances[index];
    float x = lodX[index];
    outFade = frame.counts.w > 1u ? x - floor(x) : 0.0;
    outIsFadeLod = (entry & kLodFadeEntryBit) != 0u ? 1u : 0u;
    GpuVertex v = vertices[gl_VertexIndex];
    float s = sin(inst.yaw), c = cos(inst.yaw);
    mat3 yaw = mat3(c, 0.0, -s, 0.0, 1.0, 0.0, s, 0.0, c);
    vec3 p = v.positionU.xyz, n = v.normalV.xyz;
    if (inst.positionScale.w < 0.0) {
        vec3 m = vec3(mirrorNormal.x, 0.0, mirrorNormal.z);
        p -= 2.0 * dot(p, m) * m;
        n -= 2.0 * dot(n, m) * m;
    }
    vec3 world = inst.positionScale.xyz + yaw * (p * abs(inst.positionScale.w));
    gl_Position = frame.viewProj * vec4(world, 1.0);
    outNormal = yaw * n;
    outUv = vec2(v.positionU.w, v.normalV.w);
    outTint = inst.tint;
    outHeight = v.positionU.y;
}
