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

MEADOW_FRAME_BLOCK(0, 0)
// Every read is a texel fetch, from texel views of the buffers (the compute passes' own, where they
// read the same), not a storage buffer load: llvmpipe loads a storage buffer lane by lane, each word
// behind its own branch, and a texel with one gather. The instance's words are read per vertex, and
// a LOD 0 vertex plays up to a few dozen modes, each a coordinate and a basis row, on lavapipe's one
// front-end thread (docs/BENCHMARKS.md, 2026-12-02).
layout(set = 0, binding = 1) uniform usamplerBuffer visible;       // the visible list, a word each
layout(set = 0, binding = 2) uniform usamplerBuffer drawInstances; // GpuDrawInstance: 3 texels each
layout(set = 0, binding = 3) uniform usamplerBuffer clumps;        // GpuClump: kClumpTexels each
layout(set = 0, binding = 4) uniform usamplerBuffer lodVertices; // GpuLodVertex: 3 texels each
layout(set = 0, binding = 5) uniform samplerBuffer motionData;   // the coordinates, a float each
layout(set = 0, binding = 6) uniform usamplerBuffer vertexLight;
layout(set = 0, binding = 8) uniform samplerBuffer motionRows; // motionData's basis rows, a texel each
#include "clump_motion.glsl"
#include "clump_vertex.glsl"
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
    uint entry = texelFetch(visible, gl_InstanceIndex).r;
    int record = 3 * int(entry & kLodEntryIndexMask);
    GpuDrawInstance inst;
    inst.positionScale = uintBitsToFloat(texelFetch(drawInstances, record));
    inst.pose = uintBitsToFloat(texelFetch(drawInstances, record + 1));
    inst.offsets = texelFetch(drawInstances, record + 2);
    float fade = inst.pose.w;

    // (A lavapipe crash once blamed on the motion loop's shape came from Mesa's shader cache handing
    // 256-bit vertex code to a 128-bit process: docs/ROBUSTNESS.md.)
    ClumpVertex v = shadeClumpVertex(uint(gl_VertexIndex), inst, mirrorNormal.xz);
    gl_Position = v.clip;
    outUvFacing = v.uvFacing;
    outFront = v.front;
    outBack = v.back;
    uint lod = (entry & kLodFarMeshEntryBit) != 0u ? kLodFar : v.lod;
    // w 1: constant albedo instead of the atlas.
    vec4 albedo = uintBitsToFloat(texelFetch(clumps, int(kClumpTexels * (inst.offsets.w >> 16u) + kClumpAlbedoTexel)));
    uint facts = lodDitherLevel(fade) | ((entry & kLodFadeEntryBit) != 0u ? kClumpFadeLodBit : 0u) |
                 (fade > 0.0 ? kClumpFadingBit : 0u) | (albedo.w > 0.5 ? kClumpConstantAlbedoBit : 0u) |
                 (lod << kClumpLodShift);
    outClump = uvec4(floatBitsToUint(albedo.rgb), facts);
}
