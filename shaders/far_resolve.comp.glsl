#version 460
// Far field, resolve pass: every pixel where a far-field sample won (far_splat.comp) and lies
// nearer than the meshes' depth takes its radiance in the HDR image, before tone mapping (so EXR
// output has it too). The depth test is here, once per pixel, rather than per sample in the splat
// pass: the same picture (far_splat.h, farWordShows), and no depth fetch in the splat pass's loop.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "far_splat.h"

layout(local_size_x = kFarResolveGroupSize, local_size_y = kFarResolveGroupSize) in;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Visibility { uint64_t visibility[]; };
layout(set = 0, binding = 2, rgba16f) uniform image2D hdrImage;
layout(set = 0, binding = 3) uniform sampler2D meshDepth;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(hdrImage);
    if (p.x >= size.x || p.y >= size.y)
        return;
    uvec2 word = unpackUint2x32(visibility[uint(p.y) * uint(size.x) + uint(p.x)]);
    if (!farWordShows(word.y, texelFetch(meshDepth, p, 0).r))
        return; // a mesh (or the terrain) is as near or nearer
    vec3 radiance = unpackRgb9e5(word.x);
    imageStore(hdrImage, p, vec4(radiance, 1.0));
}
