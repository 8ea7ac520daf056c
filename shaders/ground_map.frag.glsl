#version 460
// One instance's ground grid: the ratio of shaded to open-ground irradiance, bilinear between the
// grid points, multiplied into the map by the blend state (dst * src).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 3, std430) readonly buffer VertexLight { vec4 vertexLight[]; };

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
    vec3 r00 = vertexLight[inLight + z * n + x].rgb, r10 = vertexLight[inLight + z * n + x + 1u].rgb;
    vec3 r01 = vertexLight[inLight + (z + 1u) * n + x].rgb, r11 = vertexLight[inLight + (z + 1u) * n + x + 1u].rgb;
    outRatio = vec4(mix(mix(r00, r10, f.x), mix(r01, r11, f.x), f.y), 1.0);
}
