#version 460
// The sky backdrop: the library's day of sky (SKYD), two frames blended, and the sun's disk.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer SkyData { float skyData[]; };

layout(location = 0) in vec2 inClip;
layout(location = 0) out vec4 outColor;

void main() {
    vec4 farPoint = frame.inverseViewProj * vec4(inClip, 1.0, 1.0);
    vec3 dir = normalize(farPoint.xyz / farPoint.w - frame.cameraPosition.xyz);
    // Below the horizon the far ground has faded into the haze (ground.frag).
    vec3 radiance = frame.skyHorizon.rgb;
    if (dir.y >= 0.0)
        MEADOW_SKY_RADIANCE(radiance, skyData, frame, dir)
    outColor = vec4(radiance, 1.0);
}
