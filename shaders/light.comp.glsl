#version 460
// Light pass (docs/ARCHITECTURE.md, The run time): runs when the sky changes. One thread per clump
// vertex, for each of its light variants in turn: the blended sky's SH, turned into the clump's
// frame for the variant's yaw and mirror (sh_light.h), dotted with the vertex's transfer and its
// gradient. What it writes is all the vertex shader needs: irradiance = E + dE/dd . d for its
// displacement d. The clump's ground grid takes a dispatch of its own, through a pipeline of its
// own (kGroundPoints): per point and variant the ratio of its irradiance to that of open ground,
// which ground_map.comp multiplies into the field's ground light map. (One dispatch whose last
// threads did the points ran the points' code in every SIMD row, and the vertices' in the rows of
// points: llvmpipe runs both sides of a branch whatever its lanes decide; docs/BENCHMARKS.md.)
//
// A thread reads its vertex's 54 vec4s of transfer once for all the variants, and reads them as
// texel fetches: llvmpipe gathers those, where it loads a storage buffer lane by lane. A thread per
// vertex and variant, each reading the transfer from a storage buffer, took eight times the loads,
// and the pass 200 ms on a 2-core machine instead of about 25 (docs/BENCHMARKS.md, 2026-11-29).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "sh_light.h"

layout(local_size_x = kLightGroupSize) in;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Clumps { GpuClump clumps[]; };
layout(set = 0, binding = 2) uniform samplerBuffer transfer;
layout(set = 0, binding = 3, std430) readonly buffer SkyData { float skyData[]; };
// Vertex light as half floats (gpu_types.h kLightVec4sPerVertex); ground ratios as float vec4.
layout(set = 0, binding = 4, std430) writeonly buffer VertexLight { uvec4 vertexLight[]; };
layout(push_constant) uniform LightParams { uint clumpIndex; };
// false: a thread per clump vertex; true: a thread per point of the clump's ground grid.
layout(constant_id = 1) const bool kGroundPoints = false;

// The sky in the clump's frame for one light variant: yaw bin variant % bins, mirrored from
// bins on.
void skyForVariant(GpuClump clump, uint variant, float sky[27], out float local[27]) {
    uint bins = clump.light.y;
    bool mirrored = variant >= bins;
    float yaw = clump.yawBins.x + (float(variant % bins) + 0.5) * clump.yawBins.z;
    shSkyToClumpFrame(sky, shClumpFrameSign(mirrored), shClumpFrameDelta(yaw, mirrored, frame.skyBlend.y), local);
}

void main() {
    GpuClump clump = clumps[clumpIndex];
    uint variants = 2u * clump.light.y;
    uint item = gl_GlobalInvocationID.x;
    uint points = clump.ground.z * clump.ground.z;
    if (item >= (kGroundPoints ? points : clump.light.w) || variants == 0u)
        return;

    // The sky: two frames of the day, blended.
    uint stride = kSkyFrameHeaderFloats + frame.skyFrames.z * frame.skyFrames.w * 3u;
    uint a = frame.skyFrames.x * stride, b = frame.skyFrames.y * stride;
    float w = frame.skyBlend.x;
    float sky[27];
    for (uint i = 0u; i < 27u; ++i)
        sky[i] = mix(skyData[a + i], skyData[b + i], w);

    if (kGroundPoints) {
        // Open ground: the clamped cosine about +y, which no turn about +y or mirror changes.
        vec3 open = kPi * 0.282095 * vec3(sky[0], sky[1], sky[2]) +
                    2.0 * kPi / 3.0 * 0.488603 * vec3(sky[6], sky[7], sky[8]) +
                    kPi / 4.0 * 0.630784 * vec3(sky[18], sky[19], sky[20]);
        vec3 point[9];
        for (uint i = 0u; i < 9u; ++i) {
            uint at = clump.ground.x + item * 27u + i; // [point][channel][coefficient]
            point[i] = vec3(texelFetch(transfer, int(at)).x, texelFetch(transfer, int(at + 9u)).x,
                            texelFetch(transfer, int(at + 18u)).x);
        }
        // The variants' loops test at their end (a clump has variants: the return above): llvmpipe
        // runs a loop's body once for its SIMD row even where no lane enters it.
        uint variant = 0u;
        do {
            float local[27];
            skyForVariant(clump, variant, sky, local);
            vec3 shaded = vec3(0.0);
            for (uint i = 0u; i < 9u; ++i)
                shaded += point[i] * vec3(local[3u * i], local[3u * i + 1u], local[3u * i + 2u]);
            vec3 ratio = clamp(shaded / max(open, vec3(1e-9)), vec3(0.0), vec3(2.0));
            vertexLight[clump.ground.y + variant * points + item] = floatBitsToUint(vec4(ratio, 1.0));
        } while (++variant < variants);
        return;
    }
    uint t = clump.light.z + item * 54u;
    uint out0 = clump.light.x + item * variants * kLightVec4sPerVertex;
    // Side-major, then channel (transfer.h); two (E, gradient) groups per uvec4 of half floats.
    vec4 tr[54];
    for (uint i = 0u; i < 54u; ++i)
        tr[i] = texelFetch(transfer, int(t + i));
    uint variant = 0u;
    do {
        float local[27];
        skyForVariant(clump, variant, sky, local);
        for (uint k = 0u; k < 3u; ++k) {
            uint sa = 2u * k, sb = 2u * k + 1u;
            vec4 ea = vec4(0.0), eb = vec4(0.0);
            for (uint i = 0u; i < 9u; ++i) {
                ea += tr[sa * 9u + i] * local[3u * i + sa % 3u];
                eb += tr[sb * 9u + i] * local[3u * i + sb % 3u];
            }
            vertexLight[out0 + variant * kLightVec4sPerVertex + k] =
                uvec4(packHalf2x16(ea.xy), packHalf2x16(ea.zw), packHalf2x16(eb.xy), packHalf2x16(eb.zw));
        }
    } while (++variant < variants);
}
