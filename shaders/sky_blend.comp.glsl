#version 460
// The sky backdrop of this frame: the two sky frames around the hour (frame.skyFrames) blended by
// frame.skyBlend.x into one lat-long image, a thread per texel. sky.frag then reads the backdrop
// as one bilinear sample per pixel instead of 24 loads from the SkyData buffer (docs/BENCHMARKS.md);
// blending the texels before filtering is the same sum as filtering each frame and blending.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer SkyData { float skyData[]; };
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D skyImage;

void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    uint width = frame.skyFrames.z, height = frame.skyFrames.w;
    if (p.x >= width || p.y >= height)
        return;
    uint stride = kSkyFrameHeaderFloats + width * height * 3u;
    uint texel = kSkyFrameHeaderFloats + 3u * (p.y * width + p.x);
    uint a = frame.skyFrames.x * stride + texel, b = frame.skyFrames.y * stride + texel;
    vec3 first = vec3(skyData[a], skyData[a + 1u], skyData[a + 2u]);
    vec3 second = vec3(skyData[b], skyData[b + 1u], skyData[b + 2u]);
    imageStore(skyImage, ivec2(p), vec4(first * (1.0 - frame.skyBlend.x) + second * frame.skyBlend.x, 1.0));
}
