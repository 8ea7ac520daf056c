#version 460
// The ground: the terrain mesh (the field's hills, easing into a plain that reaches the horizon),
// vertices pulled from a storage buffer by gl_VertexIndex, lit per vertex by the blended sky's
// SH (unshadowed irradiance about the terrain normal; the coefficients from the frame block).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Vertices { GpuVertex vertices[]; };

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outIrradiance;

vec3 frameSky(int i) {
    return frame.skySh[i].rgb;
}

void main() {
    GpuVertex v = vertices[gl_VertexIndex];
    vec3 e;
    MEADOW_SH_IRRADIANCE(e, frameSky, normalize(v.normalV.xyz))
    outIrradiance = max(e, vec3(0.0));
    outWorld = v.positionU.xyz;
    gl_Position = frame.viewProj * vec4(outWorld, 1.0);
}
