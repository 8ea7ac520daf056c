#version 460
// The ground: the terrain mesh (the field's hills, easing into a plain that reaches the horizon),
// vertices pulled from a storage buffer by gl_VertexIndex.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Vertices { GpuVertex vertices[]; };

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;

void main() {
    GpuVertex v = vertices[gl_VertexIndex];
    outWorld = v.positionU.xyz;
    outNormal = v.normalV.xyz;
    gl_Position = frame.viewProj * vec4(outWorld, 1.0);
}
