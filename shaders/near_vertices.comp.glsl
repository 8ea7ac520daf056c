#version 460
// The near raster's first pass (near_raster.h): every vertex of each listed LOD draw moved and lit
// once, as instance.vert does it, into the near raster's vertex buffer at the draw's range, which
// the cull pass allotted. Each workgroup (on a GPU) or SIMD row (on a CPU) takes a listed draw
// (near_raster.h: dealt in turn or taken from a counter; slots take draws in work_order.h's spread
// order; a large draw is listed in parts, nearPartRange), its threads striding over the LOD mesh's
// vertices (the part's). near_raster.comp then reads three of them per triangle: shaded once
// rather than once per triangle that uses them.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "common.glsl"
#include "lod_select.h"
#include "draw_instance.h"
#include "near_raster.h"
#include "work_order.h"

// The width is the device's (near_raster.h): specialization constant 0.
layout(local_size_x = kNearGroupSize, local_size_x_id = 0) in;
// How the workgroups share the draws out (near_raster.h): dealt in turn (false) or taken by each
// SIMD row from the counter (true).
layout(constant_id = 1) const bool kTakeDraws = false;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer NearList { uvec4 nearList[]; }; // near_raster.h
layout(set = 0, binding = 2, std430) readonly buffer NearDispatch { GpuNearDispatch nearDispatch; };
layout(set = 0, binding = 3, std430) readonly buffer DrawInstances { GpuDrawInstance drawInstances[]; };
layout(set = 0, binding = 4, std430) readonly buffer NearMeshes { uvec4 nearMeshes[]; }; // near_raster.h
layout(set = 0, binding = 5) uniform usamplerBuffer lodVertices; // GpuLodVertex: 3 texels each
layout(set = 0, binding = 6) uniform samplerBuffer motionData;
layout(set = 0, binding = 7) uniform usamplerBuffer vertexLight;
layout(set = 0, binding = 8, std430) writeonly buffer NearVertices { uvec4 nearVertices[]; }; // 2 per vertex
layout(set = 0, binding = 9) uniform samplerBuffer motionRows; // motionData's basis rows, a texel each
layout(set = 0, binding = 10, std430) buffer NearTaken { uint nearTaken[2]; }; // near_raster.h
#include "near_take.glsl"
#include "clump_motion.glsl"
#include "clump_vertex.glsl"
layout(push_constant) uniform NearParams { vec4 mirrorNormal; }; // as instance.vert's

void main() {
    uint total = nearDispatch.count;
    vec2 size = frame.lodScreen.zw;
    uint stride = workStride(total);
    // Both loops test at their end (near_raster.comp's): a mesh has a vertex, and a lane past the
    // last vertex writes nothing. The threads' first draw is their workgroup's (the cull pass adds
    // one workgroup per listed draw) or the one their SIMD row took, if any was left (near_raster.h).
    NearShare share = nearShareStart(kTakeDraws, kNearTakenVertices);
    uint item = share.item;
    if (item < total) do {
        uvec4 listed = nearList[workEntry(item, total, stride)];
        GpuDrawInstance inst = drawInstances[listed.x & kLodEntryIndexMask];
        uvec4 mesh = nearMeshes[listed.y];
        uvec2 range = nearPartRange(listed.w, mesh.y); // the listed part's vertices
        uint v = range.x + share.lane;
        do {
            ClumpVertex o = shadeClumpVertex(mesh.x + min(v, mesh.y - 1u), inst, mirrorNormal.xz);
            // Every listed instance lies in front of the near plane (the cull pass's test): w > 0.
            float invW = 1.0 / o.clip.w;
            vec2 pixel = (o.clip.xy * invW * 0.5 + 0.5) * size;
            uint slot = 2u * (listed.z + v);
            if (v < range.y) {
                nearVertices[slot] = uvec4(floatBitsToUint(pixel.x), floatBitsToUint(pixel.y), floatBitsToUint(invW),
                                           floatBitsToUint(o.uvFacing.z));
                nearVertices[slot + 1u] = uvec4(packRgb9e5(o.front.r, o.front.g, o.front.b),
                                                packRgb9e5(o.back.r, o.back.g, o.back.b),
                                                floatBitsToUint(o.uvFacing.x), floatBitsToUint(o.uvFacing.y));
            }
        } while ((v += share.width) < range.y);
    } while ((item = nearShareNext(kTakeDraws, kNearTakenVertices, share, total)) < total);
}
