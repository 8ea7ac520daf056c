#version 460
// Tonemap: linear HDR radiance -> display-referred sRGB-encoded 8-bit, with an exposure and the
// ACES fit of Narkowicz (2015). Writes UNORM values already sRGB-encoded so that PNG output and
// a UNORM swapchain both show them as they are.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(local_size_x = kTonemapGroupSize, local_size_y = kTonemapGroupSize) in;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D hdrImage;
layout(set = 0, binding = 2, rgba8) uniform writeonly image2D ldrImage;

vec3 acesFilm(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 linearToSrgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(hdrImage);
    if (p.x >= size.x || p.y >= size.y)
        return;
    vec3 hdr = imageLoad(hdrImage, p).rgb * frame.skyZenith.w;
    imageStore(ldrImage, p, vec4(linearToSrgb(acesFilm(hdr)), 1.0));
}
