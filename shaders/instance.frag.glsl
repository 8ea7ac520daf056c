#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "lod_select.h"

MEADOW_FRAME_BLOCK(0, 0)
// The plants' texture atlas (sRGB texels, so samples are linear).
layout(set = 0, binding = 5) uniform sampler2D atlas;

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec2 inUv;
layout(location = 2) in float inTint;
layout(location = 3) in float inHeight;
layout(location = 4) flat in float inFade;
layout(location = 5) flat in uint inIsFadeLod;
layout(location = 0) out vec4 outColor;

void main() {
    // A crossfading instance draws in two LODs with complementary dither masks (lod_select.h).
    if (inFade > 0.0 && !lodDitherKeeps(inIsFadeLod != 0u, inFade, uint(gl_FragCoord.x), uint(gl_FragCoord.y)))
        discard;
    // Blades and petals are thin and two-sided: light the face the camera sees.
    vec3 n = normalize(inNormal) * (gl_FrontFacing ? 1.0 : -1.0);
    vec3 albedo = texture(atlas, inUv).rgb;
    // A little per-instance variation so neighbouring copies of a clump differ, and a darker
    // base where the clump shades itself (until precomputed transfer lights it properly).
    albedo *= mix(0.85, 1.1, inTint) * mix(0.55, 1.0, clamp(inHeight * 2.5, 0.0, 1.0));
    outColor = vec4(albedo * diffuseLight(frame, n), 1.0);
}
