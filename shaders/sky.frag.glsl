#version 460
// The sky backdrop: this frame's blend of the library's day of sky (SKYD; sky_blend.comp), and the
// sun's disk.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
// Bilinear, wrapping around in azimuth (u) and clamped at the poles (v).
layout(set = 0, binding = 1) uniform sampler2D skyImage;

layout(location = 0) in vec2 inClip;
layout(location = 1) flat in float inSunCosine; // cos(frame.sunColor.w), from sky.vert
layout(location = 0) out vec4 outColor;

void main() {
    vec4 farPoint = frame.inverseViewProj * vec4(inClip, 1.0, 1.0);
    vec3 dir = normalize(farPoint.xyz / farPoint.w - frame.cameraPosition.xyz);
    // Below the horizon the far ground has faded into the haze (ground.frag).
    vec3 radiance = frame.skyHorizon.rgb;
    if (dir.y >= 0.0) {
        // light/latlong.h's layout: u the azimuth from +z towards +x, v the polar angle from +y.
        float u = atan(dir.x, dir.z) / (2.0 * kPi);
        u = u < 0.0 ? u + 1.0 : u;
        float v = acos(clamp(dir.y, -1.0, 1.0)) / kPi;
        radiance = textureLod(skyImage, vec2(u, v), 0.0).rgb;
        if (dot(dir, frame.sunDirection.xyz) > inSunCosine)
            radiance += frame.sunColor.rgb;
    }
    outColor = vec4(radiance, 1.0);
}
