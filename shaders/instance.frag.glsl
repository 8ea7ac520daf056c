#version 460
// Clump fragments: the atlas (alpha-tested petals and blades) times the irradiance of the side
// the camera sees, radiance = albedo / pi * E (transfer/transfer.h); the crossfade dither.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "lod_select.h"

MEADOW_FRAME_BLOCK(0, 0)
// The plants' texture atlas (sRGB texels, so samples are linear), after the vertex stage's
// storage buffers.
layout(set = 0, binding = 7) uniform sampler2D atlas;

layout(location = 0) in vec3 inUvFacing; // uv, n . (eye - x) interpolated
layout(location = 1) in vec3 inFront;
layout(location = 2) in vec3 inBack;
layout(location = 3) flat in uvec4 inClump; // constant albedo bits, facts (common.glsl's kClump*)
layout(location = 0) out vec4 outColor;


void main() {
    // A crossfading instance draws in two LODs with complementary dither masks (lod_select.h).
    uint facts = inClump.w;
    if ((facts & kClumpFadingBit) != 0u &&
        !lodDitherKeepsLevel((facts & kClumpFadeLodBit) != 0u, facts & kClumpDitherLevelMask, uint(gl_FragCoord.x),
                             uint(gl_FragCoord.y)))
        discard;
    vec4 texel = (facts & kClumpConstantAlbedoBit) != 0u ? vec4(uintBitsToFloat(inClump.xyz), 1.0)
                                                         : texture(atlas, inUvFacing.xy);
    if (texel.a < 0.5)
        discard;
    // The side of the sheet the camera sees: the normal's side when it faces the eye.
    bool front = inUvFacing.z >= 0.0;
    vec3 radiance = texel.rgb * (front ? inFront : inBack);
    // LOD colours at a fixed display brightness (exposure divided out), the sheet's far side darker.
    if (frame.motion.z == kDebugViewLod)
        radiance = kLodViewColors[min(facts >> kClumpLodShift, kLodFar)] * (front ? 1.0 : 0.6) /
                   max(frame.skyZenith.w, 1e-6);
    outColor = vec4(radiance, 1.0);
}
