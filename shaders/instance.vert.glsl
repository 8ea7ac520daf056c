#version 460
// Instanced mesh: vertices pulled from a storage buffer, instances addressed through the visible
// list that the cull pass compacted.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer VisibleList { uint visible[]; };
layout(set = 0, binding = 3, std430) readonly buffer Vertices { GpuVertex vertices[]; };

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec3 outAlbedo;
layout(location = 2) out vec2 outUv;

void main() {
    GpuInstance inst = instances[visible[gl_InstanceIndex]];
    GpuVertex v = vertices[gl_VertexIndex];
    float s = sin(inst.boundsTint.y), c = cos(inst.boundsTint.y);
    mat3 yaw = mat3(c, 0.0, -s, 0.0, 1.0, 0.0, s, 0.0, c);
    vec3 world = inst.positionScale.xyz + yaw * (v.positionU.xyz * inst.positionScale.w);
    gl_Position = frame.viewProj * vec4(world, 1.0);
    outNormal = yaw * v.normalV.xyz;
    vec3 tint = hueToRgb(inst.boundsTint.z);
    // Greens with a little per-instance tint; darker at the base, as grass and leaves are.
    outAlbedo = mix(vec3(0.10, 0.32, 0.06), tint * 0.35, 0.15) * mix(0.45, 1.0, v.normalV.w);
    outUv = vec2(v.positionU.w, v.normalV.w);
}
