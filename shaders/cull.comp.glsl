#version 460
// Cull pass: one thread per instance. Frustum test of the instance's bounding sphere, then
// compaction of the visible instances into their mesh's range of the visible list, with that
// mesh's indirect draw's instanceCount as the atomic counter (Haar & Aaltonen 2015). Each draw's
// firstInstance is the start of its range, so the vertex shader reads visible[gl_InstanceIndex].
// The CPU reference is engine/render/cull_reference.cpp; both must agree exactly.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(local_size_x = kCullGroupSize) in;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = 2, std430) buffer DrawCommands { GpuDrawIndexedCommand draws[]; };
layout(set = 0, binding = 3, std430) writeonly buffer VisibleList { uint visible[]; };
layout(set = 0, binding = 4, std430) buffer Stats { GpuCullStats stats; };

// Sphere against the six inward-facing planes; `precise` keeps the arithmetic identical to the
// CPU reference (no fused multiply-add).
bool sphereVisible(vec3 center, float radius) {
    for (int i = 0; i < 6; ++i) {
        precise float d = dot(frame.frustumPlanes[i].xyz, center) + frame.frustumPlanes[i].w;
        if (d < -radius)
            return false;
    }
    return true;
}

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= frame.counts.x)
        return;

    GpuInstance inst = instances[index];
    float scale = abs(inst.positionScale.w); // negative: mirrored (instance.vert.glsl), same sphere
    // The sphere is centred half a radius above the base: the mesh grows up from its base.
    precise vec3 center = inst.positionScale.xyz + vec3(0.0, inst.boundingRadius * scale * 0.5, 0.0);
    precise float radius = inst.boundingRadius * scale;

    atomicAdd(stats.testedInstances, 1u);
    if (sphereVisible(center, radius)) {
        uint slot = atomicAdd(draws[inst.mesh].instanceCount, 1u);
        visible[draws[inst.mesh].firstInstance + slot] = index;
        atomicAdd(stats.visibleInstances, 1u);
    }
}
