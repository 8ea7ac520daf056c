#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
// How much light reaches the ground under and around the clumps (ground_map.comp), over the
// field's rectangle (frame.groundMap); open ground outside it.
layout(set = 0, binding = 2) uniform sampler2D groundMap;

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inIrradiance;
layout(location = 0) out vec4 outColor;

void main() {
    // Soil with a faint low-frequency variation so the ground reads as a surface, fading into
    // the horizon haze with distance. Radiance = albedo / pi * E.
    vec2 q = inWorld.xz * 0.37;
    float variation = 0.5 + 0.25 * (sin(q.x) * sin(q.y * 1.3) + sin(q.x * 0.31 + q.y * 0.17));
    vec3 albedo = mix(vec3(0.16, 0.11, 0.06), vec3(0.22, 0.18, 0.09), variation);
    vec2 uv = (inWorld.xz - frame.groundMap.xy) * frame.groundMap.zw;
    vec3 shade = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) ? texture(groundMap, uv).rgb
                                                                                           : vec3(1.0);
    vec3 color = albedo * inIrradiance * shade * (1.0 / kPi);
    float dist = length(inWorld - frame.cameraPosition.xyz);
    float haze = 1.0 - exp(-dist * 0.004);
    outColor = vec4(mix(color, frame.skyHorizon.rgb, haze), 1.0);
}
