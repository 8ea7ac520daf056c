#version 460
// Tonemap (without a far field; far_resolve.comp tone maps when there is one): the HDR image ->
// the 8-bit sRGB-encoded LDR image (tonemap.h).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "tonemap.h"

layout(local_size_x = kTonemapGroupSize, local_size_y = kTonemapGroupSize) in;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D hdrImage;
layout(set = 0, binding = 2, rgba8) uniform writeonly image2D ldrImage;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(hdrImage);
    if (p.x >= size.x || p.y >= size.y)
        return;
    imageStore(ldrImage, p, tonemapRadiance(imageLoad(hdrImage, p).rgb, frame.skyZenith.w));
}
