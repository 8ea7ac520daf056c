#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)

layout(location = 0) in vec2 inClip;
layout(location = 0) out vec4 outColor;

void main() {
    vec4 farPoint = frame.inverseViewProj * vec4(inClip, 1.0, 1.0);
    vec3 dir = normalize(farPoint.xyz / farPoint.w - frame.cameraPosition.xyz);
    outColor = vec4(skyRadiance(frame, dir), 1.0);
}
