#version 460
// Cull pass: one thread per instance. Frustum test of the instance's bounding sphere, then
// compaction of the visible instances into their mesh's range of the visible list, with that
// mesh's indirect draw's instanceCount as the atomic counter (Haar & Aaltonen 2015). Each draw's
// firstInstance is the start of its range, so the vertex shader reads visible[gl_InstanceIndex].
// The CPU reference is engine/render/cull_reference.cpp; both must agree exactly.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "lod_select.h"
#include "draw_instance.h"
#include "far_splat.h"
#include "near_raster.h"

layout(local_size_x = kCullGroupSize) in;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = 2, std430) buffer DrawCommands { GpuDrawIndexedCommand draws[]; };
layout(set = 0, binding = 3, std430) writeonly buffer VisibleList { uint visible[]; };
layout(set = 0, binding = 4, std430) buffer Stats { GpuCullStats stats; };
layout(set = 0, binding = 5, std430) buffer LodState { float lodX[]; };
layout(set = 0, binding = 6, std430) readonly buffer Clumps { GpuClump clumps[]; };
layout(set = 0, binding = 7, std430) readonly buffer MotionStates { GpuMotionState states[]; };
// Per visible instance, what its vertices need (draw_instance.h), indexed like the instances.
layout(set = 0, binding = 8, std430) writeonly buffer DrawInstances { GpuDrawInstance drawInstances[]; };
// The far field (far_splat.h): per far instance its entry (the fade bit when it is the second
// draw of a crossfade from LOD 4) and the samples it draws; the splat pass's dispatch.
layout(set = 0, binding = 9, std430) writeonly buffer FarList { uvec2 farList[]; };
layout(set = 0, binding = 10, std430) buffer FarDispatch { GpuFarDispatch farDispatch; };
// The near raster (near_raster.h): the LOD draws it takes, its dispatch and where its meshes lie.
layout(set = 0, binding = 11, std430) writeonly buffer NearList { uvec4 nearList[]; };
layout(set = 0, binding = 12, std430) buffer NearDispatch { GpuNearDispatch nearDispatch; };
layout(set = 0, binding = 13, std430) readonly buffer NearMeshes { uvec4 nearMeshes[]; };

void append(uint bucket, uint entry) {
    uint slot = atomicAdd(draws[bucket].instanceCount, 1u);
    visible[draws[bucket].firstInstance + slot] = entry;
}

// An instance's draw of the mesh in bucket `bucket`: by the near raster when the instance is given a
// subpixel grid (sub > 0) and there is room for its vertices in the near raster's vertex buffer,
// with one more workgroup for each of its entries (a large draw has kNearDrawParts); otherwise by
// the draw pass.
void appendLod(uint bucket, uint entry, int sub) {
    if (sub > 0) {
        uvec4 mesh = nearMeshes[bucket];
        uint start = atomicAdd(nearDispatch.vertices, mesh.y);
        if (start + mesh.y <= kNearMaxVertices && start + mesh.y >= start) {
            // A large draw in parts, while the list has room for them (near_raster.h).
            uint parts = 1u;
            if (nearSplitsDraw(sub) && atomicAdd(nearDispatch.split, 1u) < kNearMaxSplitDraws)
                parts = kNearDrawParts;
            uint slot = atomicAdd(nearDispatch.count, parts);
            uint part = 0u;
            do
                nearList[slot + part] = uvec4(entry, bucket, start, nearListedWord(sub, part, parts));
            while (++part < parts);
            uint groups = min(slot + parts, kNearMaxGroups) - min(slot, kNearMaxGroups);
            if (groups > 0u)
                atomicAdd(nearDispatch.groupsX, groups);
            atomicAdd(stats.nearInstances, 1u);
            atomicAdd(stats.nearTriangles, mesh.w / 3u);
            atomicAdd(stats.nearPerLod[bucket % frame.counts.w], 1u);
            return;
        }
    }
    append(bucket, entry);
}

// A far instance: as many of its clump's samples as its projected surface wants; one more
// workgroup for the splat pass per kFarInstancesPerGroup of them, up to kFarMaxGroups.
void appendFar(uint entry, GpuClump clump, float scale, float pixelsPerMetre) {
    float area = uintBitsToFloat(clump.far.z) * scale * scale;
    uint count = farSampleCount(area, pixelsPerMetre, frame.lodScreen.y, clump.far.y);
    uint slot = atomicAdd(farDispatch.count, 1u);
    farList[slot] = uvec2(entry, count);
    if (slot % kFarInstancesPerGroup == 0u && slot / kFarInstancesPerGroup < kFarMaxGroups)
        atomicAdd(farDispatch.groupsX, 1u);
    atomicAdd(stats.farInstances, 1u);
    atomicAdd(stats.farSamples, count);
}

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
        atomicAdd(stats.visibleInstances, 1u);
        uint lodCount = frame.counts.w;
        uint first = inst.mesh * lodCount;
        if (lodCount <= 1u) {
            drawInstances[index] = makeDrawInstance(inst, clumps[inst.mesh], states[index], 0.0, false);
            append(first, index);
            return;
        }
        // The sphere's projected radius in pixels picks the LOD (lod_select.h); the instance's
        // coordinate is kept for the hysteresis of the next frame.
        precise float dist = max(length(center - frame.cameraPosition.xyz), 1e-3);
        precise float screenRadius = radius * frame.lodScreen.x / dist;
        GpuLodParams p;
        p.switchRadius[0] = frame.lodSwitchRadius.x;
        p.switchRadius[1] = frame.lodSwitchRadius.y;
        p.switchRadius[2] = frame.lodSwitchRadius.z;
        p.switchRadius[3] = frame.lodSwitchRadius.w;
        p.band = frame.lodBand.x;
        p.jitter = frame.lodBand.y;
        p.hysteresis = frame.lodBand.z;
        p.farRadius = frame.lodBand.w;
        GpuLodChoice c = lodSelect(p, screenRadius, lodInstanceRandom(index), lodX[index]);
        lodX[index] = c.x;
        drawInstances[index] = makeDrawInstance(inst, clumps[inst.mesh], states[index], c.x, true);
        // Below the far radius the far field replaces the last mesh LOD (only when the frame has one).
        bool far = c.lod == kLodFar, farFade = c.fadeLod == kLodFar && !far;
        uint lod = min(c.lod, lodCount - 1u), fadeLod = min(c.fadeLod, lodCount - 1u);
        // The mesh LODs go to the near raster when it is on, the instance is small enough on the
        // screen and its sphere lies wholly in front of the near plane (frustum plane 4).
        precise float nearDistance = dot(frame.frustumPlanes[4].xyz, center) + frame.frustumPlanes[4].w;
        int sub = (frame.motion.w & kFrameNearRaster) != 0u && screenRadius <= kNearMaxRadius && nearDistance > radius
                      ? nearSubpixelFor(screenRadius)
                      : 0;
        if (!far)
            appendLod(first + lod, index, sub);
        if (fadeLod != lod && !farFade)
            appendLod(first + fadeLod, index | kLodFadeEntryBit, sub);
        if ((far || farFade) && (frame.motion.w & kFrameFarAsLod0) != 0u) {
            // The far field's reference: the instance at LOD 0 in its place, marked for the LOD view.
            append(first, (farFade ? index | kLodFadeEntryBit : index) | kLodFarMeshEntryBit);
            atomicAdd(stats.farInstances, 1u);
        } else if (far || farFade) {
            // The samples follow the surface's projected area at the sphere's centre: its depth
            // (clip w, written out so that the CPU's sums match) and distance (farPixelsPerMetre).
            precise float depth = max(frame.viewProj[0][3] * center.x + frame.viewProj[1][3] * center.y +
                                          frame.viewProj[2][3] * center.z + frame.viewProj[3][3],
                                      1e-3);
            appendFar(farFade ? index | kLodFadeEntryBit : index, clumps[inst.mesh], scale,
                      farPixelsPerMetre(frame.lodScreen.x, depth, dist));
        }
    }
}
