#version 460
// The ground light map (render/ground_light_map.h): one thread per texel, multiplying in, in list
// order, the ratio of shaded to open-ground irradiance of every grid cell listed for the texel
// (bilinear between the cell's corners, with the weights laid out at load). Runs when the light
// pass does, after it. Every read is a texel fetch: llvmpipe gathers those where it would load a
// storage buffer lane by lane (docs/BENCHMARKS.md).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(local_size_x = kRowRunWidth, local_size_y = 1) in; // gpu_types.h

layout(set = 0, binding = 0) uniform usamplerBuffer texelStart; // per texel, then the end
layout(set = 0, binding = 1) uniform usamplerBuffer entries;    // uvec2 per listed cell
layout(set = 0, binding = 2) uniform usamplerBuffer vertexLight;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D groundLight;

vec3 ratioAt(uint texel) {
    return uintBitsToFloat(texelFetch(vertexLight, int(texel)).rgb);
}

void main() {
    ivec2 size = imageSize(groundLight);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= size.x || texel.y >= size.y)
        return;
    int t = texel.y * size.x + texel.x;
    uint begin = texelFetch(texelStart, t).r, end = texelFetch(texelStart, t + 1).r;
    const uint weightMask = (1u << kGroundWeightBits) - 1u;
    const float unit = 1.0 / float(weightMask);
    vec3 light = vec3(1.0);
    // The loop tests at its end, behind its guard: llvmpipe runs a loop's body once for its SIMD
    // row even where no lane enters it, so a loop tested at its start ran one entry's fetches and
    // multiply more than the row's longest list, for no lane (docs/BENCHMARKS.md). The same
    // entries in the same order, the same bytes.
    if (begin < end) {
        uint e = begin;
        do {
            uvec2 cell = texelFetch(entries, int(e)).rg;
            uint corner = cell.x, n = (cell.y >> (2u * kGroundWeightBits)) + 1u;
            vec2 f = vec2(cell.y & weightMask, (cell.y >> kGroundWeightBits) & weightMask) * unit;
            vec3 r00 = ratioAt(corner), r10 = ratioAt(corner + 1u);
            vec3 r01 = ratioAt(corner + n), r11 = ratioAt(corner + n + 1u);
            light *= mix(mix(r00, r10, f.x), mix(r01, r11, f.x), f.y);
        } while (++e < end);
    }
    imageStore(groundLight, texel, vec4(light, 1.0));
}
