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
#include "draw_instance.h"
#include "clump_vertex.glsl"

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer VisibleList { uint visible[]; };
layout(set = 0, binding = 2, std430) readonly buffer DrawInstances { GpuDrawInstance drawInstances[]; };
layout(set = 0, binding = 3, std430) readonly buffer Clumps { GpuClump clumps[]; };
layout(set = 0, binding = 4, std430) readonly buffer LodVertices { GpuLodVertex lodVertices[]; };
layout(set = 0, binding = 5, std430) readonly buffer MotionData { float motionData[]; };
layout(set = 0, binding = 6, std430) readonly buffer VertexLight { uvec4 vertexLight[]; };
// xz: the unit normal of the vertical plane that holds the wind direction the clumps were
// simulated in. A mirrored instance (negative scale) reflects about it before its yaw, so it
// still sways downwind (placement/instance.h).
layout(push_constant) uniform InstanceParams { vec4 mirrorNormal; };

// The varyings, in as few slots as they fit (lavapipe clips and sets up every slot of every
// triangle on one thread; each slot costs about as much as a vec4):
//   - uv, then which side of the sheet faces the eye, interpolated: n . (eye - x) at each vertex.
//     (Cheaper than the normal and position it replaces. The sign differs from the per-pixel test
//     only on a few pixels of sheets seen edge on: 0.003 % of a 960x540 frame.)
//   - irradiance / pi of the side the normal points to, and of the other side;
//   - flat: the constant albedo's float bits (xyz) and the draw's facts (w, common.glsl's kClump*).
layout(location = 0) out vec3 outUvFacing;
layout(location = 1) out vec3 outFront;
layout(location = 2) out vec3 outBack;
layout(location = 3) flat out uvec4 outClump;

void main() {
    uint entry = visible[gl_InstanceIndex];
    GpuDrawInstance inst = drawInstances[entry & kLodEntryIndexMask];
    float fade = inst.pose.w;

    GpuLodVertex v = lodVertices[gl_VertexIndex];
    uint rank = v.motion.w & 0xffffu;
    uint lod = (entry & kLodFarMeshEntryBit) != 0u ? kLodFar : v.motion.w >> 16u;

    // x̄ + U q, q blended across a graph jump (motion_step.h): the old path's weight fades from 1.
    // (Vertex shading is lavapipe's single-threaded stage: loads are what it pays for, so the old
    // path's coordinates are read only while a blend runs.)
    // (A lavapipe crash once blamed on this loop's shape came from Mesa's shader cache handing
    // 256-bit vertex code to a 128-bit process: docs/ROBUSTNESS.md.)
    uint q0 = inst.offsets.x + v.motion.y, q1 = inst.offsets.y + v.motion.y;
    bool blending = inst.pose.z > 0.0;
    vec3 d = vec3(0.0);
    for (uint k = 0u; k < rank; ++k) {
        uint row = 4u * (v.motion.x + k);
        float q = motionData[q0 + k];
        if (blending)
            q = mix(q, motionData[q1 + k], inst.pose.z);
        d += vec3(motionData[row], motionData[row + 1u], motionData[row + 2u]) * q;
    }

    // Irradiance of both sides to first order in d, for this instance's light variant (its yaw
    // bin, mirrored or not: light.comp), from half floats: (E, gradient) per side and channel.
    uint base = inst.offsets.z + v.motion.z * (inst.offsets.w & 0xffffu);
    clumpVertexLight(vertexLight[base], vertexLight[base + 1u], vertexLight[base + 2u], d, outFront, outBack);

    vec3 n = v.normalV.xyz;
    vec3 world = clumpVertexWorld(inst, v.positionU.xyz + d, n, mirrorNormal.xz);
    gl_Position = frame.viewProj * vec4(world, 1.0);
    outUvFacing = vec3(v.positionU.w, v.normalV.w, dot(n, frame.cameraPosition.xyz - world));
    vec4 albedo = clumps[inst.offsets.w >> 16u].albedo; // w 1: constant albedo instead of the atlas
    uint facts = lodDitherLevel(fade) | ((entry & kLodFadeEntryBit) != 0u ? kClumpFadeLodBit : 0u) |
                 (fade > 0.0 ? kClumpFadingBit : 0u) | (albedo.w > 0.5 ? kClumpConstantAlbedoBit : 0u) |
                 (lod << kClumpLodShift);
    outClump = uvec4(floatBitsToUint(albedo.rgb), facts);
}
