#version 460
// Far field, resolve pass, which is also the tone mapper when the far field is on: every pixel where
// a far-field sample won (far_splat.comp) and lies nearer than the meshes' surface anywhere in the
// pixel (far_splat.h, farWordShows) takes that sample's radiance, written into the HDR image (so
// EXR output has it too; not where only the LDR image is read, kStoreHdr); then the pixel is tone
// mapped into the LDR image as tonemap.comp does (tonemap.h). The depth test is here, once per
// pixel, rather than per sample in the splat pass: the same picture (far_splat.h, farWordShows),
// and no depth fetch in the splat pass's loop. One pass instead of a resolve and a tone map: each
// pixel's HDR value is read and written once (docs/BENCHMARKS.md).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "far_splat.h"
#include "tonemap.h"

layout(local_size_x = kRowRunWidth, local_size_y = 1) in; // gpu_types.h
// Whether the far field's pixels are stored into the HDR image too (render_targets.h, HdrContents):
// false where only the LDR image is read after the frame.
layout(constant_id = 1) const bool kStoreHdr = true;

MEADOW_FRAME_BLOCK(0, 0)
// The visibility buffer's words as (low, high) texels: a texel fetch where llvmpipe would load a
// storage buffer lane by lane (docs/BENCHMARKS.md, "The resolve reads the words as texels").
layout(set = 0, binding = 1) uniform usamplerBuffer visibility;
layout(set = 0, binding = 2, rgba16f) uniform image2D hdrImage;
// The meshes' depth, through a nearest sampler clamped to the edge.
layout(set = 0, binding = 3) uniform sampler2D meshDepth;
layout(set = 0, binding = 4, rgba8) uniform writeonly image2D ldrImage;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(hdrImage);
    if (p.x >= size.x || p.y >= size.y)
        return;
    uvec2 word = texelFetch(visibility, p.y * size.x + p.x).xy;
    vec3 radiance;
    // The meshes' depth at the pixel and its four neighbours, clamped at the image's edges (the
    // sampler clamps to the edge), in two gathers of 2x2 texels rather than five fetches: one at
    // the pixel's upper left corner (x: left, y: the pixel, z: above) and one at its lower right
    // (x: below, z: right). A corner lies half a texel from where a gather's footprint changes, so
    // rounding cannot move it. llvmpipe works out one footprint's addresses once for its four
    // texels: the pass takes about 3 ms less on lavapipe, the same bytes (docs/BENCHMARKS.md).
    vec2 texel = 1.0 / vec2(size);
    vec4 upperLeft = textureGather(meshDepth, vec2(p) * texel);
    vec4 lowerRight = textureGather(meshDepth, vec2(p + 1) * texel);
    float meshLimit = farMeshDepthLimit(upperLeft.y, upperLeft.x, lowerRight.z, upperLeft.z, lowerRight.x);
    if (farWordShows(word.y, meshLimit)) {
        // RGB9E5 converts to half floats exactly (9-bit mantissas, exponents from -24 to 15), so
        // the LDR pixel is the HDR image's tone mapped, as without the far field.
        radiance = unpackRgb9e5(word.x);
        if (kStoreHdr)
            imageStore(hdrImage, p, vec4(radiance, 1.0));
    } else {
        radiance = imageLoad(hdrImage, p).rgb; // a mesh (or the terrain, or the sky) is as near or nearer
    }
    imageStore(ldrImage, p, tonemapRadiance(radiance, frame.skyZenith.w));
}
