#version 460
// Build-time check that shaders/shared/far_splat.h compiles as GLSL (the far field's splat and
// resolve passes will include it): one visibility word per invocation. Not a render pass.
#extension GL_GOOGLE_include_directive : require
#include "far_splat.h"

layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer Samples { vec4 depthAndRadiance[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Words { uvec2 words[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Decoded { vec4 decoded[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= depthAndRadiance.length())
        return;
    vec4 s = depthAndRadiance[i];
    uint colour = packRgb9e5(s.y, s.z, s.w);
    words[i] = uvec2(colour, farDepthKey(s.x));
    uint count = farSampleCount(s.y, s.z, 2.0, 4096u);
    float footprint = farSampleFootprint(s.y / float(count), s.z, s.w);
    decoded[i] = vec4(unpackRgb9e5(colour), float(farSplatSide(footprint)) + farSampleRandom(i, count));
}
