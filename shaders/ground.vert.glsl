#version 460
// The ground: the terrain mesh (the field's hills, easing into a plain that reaches the horizon),
// vertices pulled from a storage buffer by gl_VertexIndex, lit per vertex by the blended sky's
// SH (unshadowed irradiance about the terrain normal).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Vertices { GpuVertex vertices[]; };
layout(set = 0, binding = 2, std430) readonly buffer SkyData { float skyData[]; };

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outIrradiance;

uint gSkyA, gSkyB;
vec3 blendedSky(int i) {
    vec3 a = vec3(skyData[gSkyA + 3 * i], skyData[gSkyA + 3 * i + 1], skyData[gSkyA + 3 * i + 2]);
    vec3 b = vec3(skyData[gSkyB + 3 * i], skyData[gSkyB + 3 * i + 1], skyData[gSkyB + 3 * i + 2]);
    return mix(a, b, frame.skyBlend.x);
}

void main() {
    GpuVertex v = vertices[gl_VertexIndex];
    uint stride = kSkyFrameHeaderFloats + frame.skyFrames.z * frame.skyFrames.w * 3u;
    gSkyA = frame.skyFrames.x * stride;
    gSkyB = frame.skyFrames.y * stride;
    vec3 e;
    MEADOW_SH_IRRADIANCE(e, blendedSky, normalize(v.normalV.xyz))
    outIrradiance = max(e, vec3(0.0));
    outWorld = v.positionU.xyz;
    gl_Position = frame.viewProj * vec4(outWorld, 1.0);
}
