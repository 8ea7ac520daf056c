#version 460
// Sky backdrop: a full-screen triangle infinitely far (depth 0 with reversed Z), drawn last where
// the depth test finds nothing nearer.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)

layout(location = 0) out vec2 outClip;
// The cosine of the sun's angular radius, worked out once per vertex rather than per pixel: lavapipe
// evaluates cos as a polynomial in every fragment, about 0.7 ms of the low view's draw pass
// (docs/BENCHMARKS.md, "The sun's cosine per vertex"). The same value at all three vertices.
layout(location = 1) flat out float outSunCosine;

void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2) * 2.0 - 1.0;
    outClip = p;
    outSunCosine = cos(frame.sunColor.w);
    gl_Position = vec4(p, 0.0, 1.0);
}
