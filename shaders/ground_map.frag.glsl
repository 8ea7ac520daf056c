#version 460
// One instance's ground grid: the ratio of shaded to open-ground irradiance, bilinear between the
// grid points, multiplied into the map by the blend state (dst * src).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
// The vertex-light buffer as uint texels (a texel buffer: llvmpipe gathers it where it would load a
// storage buffer lane by lane; docs/BENCHMARKS.md).
layout(set = 0, binding = 3) uniform usamplerBuffer vertexLight;

vec3 ratioAt(uint texel) {
    return uintBitsToFloat(texelFetch(vertexLight, int(texel)).rgb);
}

layout(location = 0) in vec2 inGrid;
layout(location = 1) flat in uint inLight;
layout(location = 2) flat in uint inResolution;
layout(location = 0) out vec4 outRatio;

void main() {
    float last = float(inResolution - 1u);
    vec2 g = clamp(inGrid, vec2(0.0), vec2(last));
    vec2 cell = min(floor(g), vec2(last - 1.0));
    vec2 f = g - cell;
    uint x = uint(cell.x), z = uint(cell.y), n = inResolution;
    vec3 r00 = ratioAt(inLight + z * n + x), r10 = ratioAt(inLight + z * n + x + 1u);
    vec3 r01 = ratioAt(inLight + (z + 1u) * n + x), r11 = ratioAt(inLight + (z + 1u) * n + x + 1u);
    outRatio = vec4(mix(mix(r00, r10, f.x), mix(r01, r11, f.x), f.y), 1.0);
}
