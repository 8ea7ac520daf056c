#version 460
// Instanced clumps: each vertex is a LOD vertex (a clump vertex and the modes this LOD plays),
// pulled by gl_VertexIndex; each instance comes from the visible list that the cull pass
// compacted (this draw's range starts at its firstInstance, which gl_InstanceIndex includes).
// The vertex moves to x̄ + U q at the instance's motion frame, blended with the frame its old
// path would show after a graph jump, and takes the irradiance the light pass projected for its
// clump vertex, to first order in that displacement (light/vertex_appearance.h).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "lod_select.h"

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer VisibleList { uint visible[]; };
layout(set = 0, binding = 3, std430) readonly buffer LodState { float lodX[]; };
layout(set = 0, binding = 4, std430) readonly buffer Clumps { GpuClump clumps[]; };
layout(set = 0, binding = 5, std430) readonly buffer PlantVertices { GpuPlantVertex plantVertices[]; };
layout(set = 0, binding = 6, std430) readonly buffer LodVertices { GpuLodVertex lodVertices[]; };
layout(set = 0, binding = 7, std430) readonly buffer MotionData { float motionData[]; };
layout(set = 0, binding = 8, std430) readonly buffer MotionStates { GpuMotionState states[]; };
layout(set = 0, binding = 9, std430) readonly buffer VertexLight { vec4 vertexLight[]; };
// xz: the unit normal of the vertical plane that holds the wind direction the clumps were
// simulated in. A mirrored instance (negative scale) reflects about it before its yaw, so it
// still sways downwind (placement/instance.h).
layout(push_constant) uniform InstanceParams { vec4 mirrorNormal; };

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec2 outUv;
layout(location = 2) out vec3 outWorld;
layout(location = 3) out vec3 outFront; // irradiance / pi of the side the normal points to
layout(location = 4) out vec3 outBack;
layout(location = 5) flat out vec4 outAlbedo; // w 1: constant albedo instead of the atlas
// The crossfade (lod_select.h): this draw's share and whether it is the instance's fadeLod.
layout(location = 6) flat out float outFade;
layout(location = 7) flat out uint outIsFadeLod;
layout(location = 8) flat out uint outLod;

void main() {
    uint entry = visible[gl_InstanceIndex];
    uint index = entry & ~kLodFadeEntryBit;
    GpuInstance inst = instances[index];
    // Only the fields used: lavapipe (Mesa 22.3) at 128-bit vectors corrupted its heap copying the
    // whole GpuClump into the vertex shader's locals.
    uvec4 clumpMotion = clumps[inst.mesh].motion;
    uvec4 clumpLight = clumps[inst.mesh].light;
    vec4 clumpYaw = clumps[inst.mesh].yawBins;
    uint blendFrames = clumps[inst.mesh].graphSizes.z;
    float x = lodX[index];
    outFade = frame.counts.w > 1u ? x - floor(x) : 0.0;
    outIsFadeLod = (entry & kLodFadeEntryBit) != 0u ? 1u : 0u;

    GpuLodVertex lv = lodVertices[gl_VertexIndex];
    GpuPlantVertex v = plantVertices[lv.vertex];
    uint rank = lv.rankLod & 0xffffu;
    outLod = lv.rankLod >> 16u;

    // x̄ + U q, q blended across a graph jump (motion_step.h): the old path's weight fades from 1.
    GpuMotionState state = states[index];
    float blend = state.blendFramesLeft > 0u ? float(state.blendFramesLeft) / float(blendFrames) : 0.0;
    uint q0 = clumpMotion.y + state.frame * clumpMotion.z + v.motion.y;
    uint q1 = clumpMotion.y + state.blendFrom * clumpMotion.z + v.motion.y;
    vec3 d = vec3(0.0);
    for (uint k = 0u; k < rank; ++k) {
        uint row = v.motion.x + 3u * k;
        float q = mix(motionData[q0 + k], motionData[q1 + k], blend);
        d += vec3(motionData[row], motionData[row + 1u], motionData[row + 2u]) * q;
    }

    // Irradiance of both sides to first order in d, for this instance's light variant (its yaw
    // bin, mirrored or not: light.comp).
    bool mirrored = inst.positionScale.w < 0.0;
    uint bins = clumpLight.y;
    int bin = clamp(int(floor((inst.yaw - clumpYaw.x) * clumpYaw.y)), 0, int(bins) - 1);
    uint variant = uint(bin) + (mirrored ? bins : 0u);
    uint base = clumpLight.x + (v.motion.z * 2u * bins + variant) * kLightVec4sPerVertex;
    vec4 l0 = vertexLight[base], l1 = vertexLight[base + 1u], l2 = vertexLight[base + 2u];
    vec4 l3 = vertexLight[base + 3u], l4 = vertexLight[base + 4u], l5 = vertexLight[base + 5u];
    outFront = max(vec3(l0.x + dot(l0.yzw, d), l1.x + dot(l1.yzw, d), l2.x + dot(l2.yzw, d)), 0.0) / kPi;
    outBack = max(vec3(l3.x + dot(l3.yzw, d), l4.x + dot(l4.yzw, d), l5.x + dot(l5.yzw, d)), 0.0) / kPi;

    vec3 p = v.positionU.xyz + d, n = v.normalV.xyz;
    if (mirrored) {
        vec3 m = vec3(mirrorNormal.x, 0.0, mirrorNormal.z);
        p -= 2.0 * dot(p, m) * m;
        n -= 2.0 * dot(n, m) * m;
    }
    float s = sin(inst.yaw), c = cos(inst.yaw);
    mat3 yaw = mat3(c, 0.0, -s, 0.0, 1.0, 0.0, s, 0.0, c);
    vec3 world = inst.positionScale.xyz + yaw * (p * abs(inst.positionScale.w));
    gl_Position = frame.viewProj * vec4(world, 1.0);
    outWorld = world;
    outNormal = yaw * n;
    outUv = vec2(v.positionU.w, v.normalV.w);
    outAlbedo = clumps[inst.mesh].albedo;
}
