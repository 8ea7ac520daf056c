#version 460
// Light pass (docs/ARCHITECTURE.md, The run time): runs when the sky changes. One thread per clump
// vertex and light variant: the blended sky's SH, turned into the clump's frame for the variant's
// yaw and mirror (sh_light.h), dotted with the vertex's transfer and its gradient. What it writes
// is all the vertex shader needs: irradiance = E + dE/dd . d for its displacement d. Threads past
// the vertices do the clump's ground grid: per point the ratio of its irradiance to that of open
// ground, which ground_map.frag multiplies into the field's ground light map.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "sh_light.h"

layout(local_size_x = kLightGroupSize) in;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Clumps { GpuClump clumps[]; };
layout(set = 0, binding = 2, std430) readonly buffer Transfer { vec4 transfer[]; };
layout(set = 0, binding = 3, std430) readonly buffer SkyData { float skyData[]; };
// Vertex light as half floats (gpu_types.h kLightVec4sPerVertex); ground ratios as float vec4.
layout(set = 0, binding = 4, std430) writeonly buffer VertexLight { uvec4 vertexLight[]; };
layout(push_constant) uniform LightParams { uint clumpIndex; };

void main() {
    GpuClump clump = clumps[clumpIndex];
    uint variants = 2u * clump.light.y;
    uint thread = gl_GlobalInvocationID.x;
    uint points = clump.ground.z * clump.ground.z;
    uint vertexThreads = clump.light.w * variants;
    if (thread >= vertexThreads + points * variants)
        return;
    bool ground = thread >= vertexThreads;
    uint item = ground ? thread - vertexThreads : thread;
    uint vertex = item / variants, variant = item % variants;

    // The sky: two frames of the day, blended.
    uint stride = kSkyFrameHeaderFloats + frame.skyFrames.z * frame.skyFrames.w * 3u;
    uint a = frame.skyFrames.x * stride, b = frame.skyFrames.y * stride;
    float w = frame.skyBlend.x;
    float sky[27];
    for (uint i = 0u; i < 27u; ++i)
        sky[i] = mix(skyData[a + i], skyData[b + i], w);

    // Into the clump's frame for this variant: the centre of its yaw bin, mirrored or not.
    uint bins = clump.light.y;
    bool mirrored = variant >= bins;
    float yaw = clump.yawBins.x + (float(variant % bins) + 0.5) * clump.yawBins.z;
    float local[27];
    shSkyToClumpFrame(sky, shClumpFrameSign(mirrored), shClumpFrameDelta(yaw, mirrored, frame.skyBlend.y), local);

    if (ground) {
        // Open ground: the clamped cosine about +y, which no turn about +y or mirror changes.
        vec3 open = kPi * 0.282095 * vec3(local[0], local[1], local[2]) +
                    2.0 * kPi / 3.0 * 0.488603 * vec3(local[6], local[7], local[8]) +
                    kPi / 4.0 * 0.630784 * vec3(local[18], local[19], local[20]);
        vec3 shaded = vec3(0.0);
        for (uint i = 0u; i < 9u; ++i) {
            uint at = clump.ground.x + vertex * 27u + i; // [point][channel][coefficient]
            shaded += vec3(transfer[at].x, transfer[at + 9u].x, transfer[at + 18u].x) *
                      vec3(local[3u * i], local[3u * i + 1u], local[3u * i + 2u]);
        }
        vec3 ratio = clamp(shaded / max(open, vec3(1e-9)), vec3(0.0), vec3(2.0));
        vertexLight[clump.ground.y + variant * points + vertex] = floatBitsToUint(vec4(ratio, 1.0));
        return;
    }
    uint t = clump.light.z + vertex * 54u;
    uint out0 = clump.light.x + (vertex * variants + variant) * kLightVec4sPerVertex;
    // Side-major, then channel (transfer.h); two (E, gradient) groups per uvec4 of half floats.
    for (uint k = 0u; k < 3u; ++k) {
        uint sa = 2u * k, sb = 2u * k + 1u;
        vec4 a = vec4(0.0), b = vec4(0.0);
        for (uint i = 0u; i < 9u; ++i) {
            a += transfer[t + sa * 9u + i] * local[3u * i + sa % 3u];
            b += transfer[t + sb * 9u + i] * local[3u * i + sb % 3u];
        }
        vertexLight[out0 + k] = uvec4(packHalf2x16(a.xy), packHalf2x16(a.zw), packHalf2x16(b.xy), packHalf2x16(b.zw));
    }
}
