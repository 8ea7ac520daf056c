#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inIrradiance;
layout(location = 0) out vec4 outColor;

void main() {
    // Soil with a faint low-frequency variation so the ground reads as a surface, fading into
    // the horizon haze with distance. Radiance = albedo / pi * E.
    vec2 q = inWorld.xz * 0.37;
    float variation = 0.5 + 0.25 * (sin(q.x) * sin(q.y * 1.3) + sin(q.x * 0.31 + q.y * 0.17));
    vec3 albedo = mix(vec3(0.16, 0.11, 0.06), vec3(0.22, 0.18, 0.09), variation);
    vec3 color = albedo * inIrradiance * (1.0 / kPi);
    float dist = length(inWorld - frame.cameraPosition.xyz);
    float haze = 1.0 - exp(-dist * 0.004);
    outColor = vec4(mix(color, frame.skyHorizon.rgb, haze), 1.0);
}
