#version 460
// The near raster (near_raster.h): the LOD draws the cull pass listed for it, drawn triangle by
// triangle in compute into the far field's visibility buffer, instead of through the graphics
// pipeline (on lavapipe, its one front-end thread; on a GPU, its few geometry units). Each
// workgroup (on a GPU) or SIMD row (on a CPU) takes a listed draw (near_raster.h: dealt in turn or
// taken from a counter; slots take draws in work_order.h's spread order; a large draw is listed in
// parts, nearPartRange), its threads striding over the LOD mesh's triangles (the part's), whose
// vertices near_vertices.comp moved and lit. Each covered pixel is lit as instance.frag lights it
// (the crossfade dither, the atlas's alpha test at the mip of the triangle's texel density, the
// side the eye sees) and merged with a 64-bit atomicMin of (depth key, RGB9E5 radiance), as the
// splat pass merges samples. far_resolve.comp then shows the winners that are nearer than the
// meshes.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_EXT_shader_atomic_int64 : require
#include "common.glsl"
#include "lod_select.h"
#include "draw_instance.h"
#include "near_raster.h"
#include "work_order.h"

// The width is the device's (near_raster.h): specialization constant 0.
layout(local_size_x = kNearGroupSize, local_size_x_id = 0) in;
// Whether the frame shows the LOD view (a debug view; frame.motion.z): a pipeline of its own, for
// llvmpipe runs an `if`'s body whatever the lanes decide, and the view's colours, tested and
// looked up per pixel, cost about 4 ms of the default view with the view off (docs/BENCHMARKS.md).
layout(constant_id = 1) const bool kLodView = false;
// How the workgroups share the draws out (near_raster.h): dealt in turn (false) or taken by each
// SIMD row from the counter (true).
layout(constant_id = 2) const bool kTakeDraws = false;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer NearList { uvec4 nearList[]; }; // near_raster.h
layout(set = 0, binding = 2, std430) readonly buffer NearDispatch { GpuNearDispatch nearDispatch; };
layout(set = 0, binding = 3, std430) readonly buffer DrawInstances { GpuDrawInstance drawInstances[]; };
layout(set = 0, binding = 4, std430) readonly buffer Clumps { GpuClump clumps[]; };
layout(set = 0, binding = 5, std430) readonly buffer NearMeshes { uvec4 nearMeshes[]; }; // near_raster.h
layout(set = 0, binding = 6) uniform usamplerBuffer indices;
layout(set = 0, binding = 7) uniform usamplerBuffer nearVertices; // near_vertices.comp's, 2 texels each
layout(set = 0, binding = 8) uniform sampler2D atlas;
layout(set = 0, binding = 9, std430) buffer Visibility { uint64_t visibility[]; };
layout(set = 0, binding = 10, std430) buffer NearTaken { uint nearTaken[2]; }; // near_raster.h
#include "near_take.glsl"

// One shaded vertex (near_vertices.comp).
struct NearVertex {
    vec2 pixel;
    float invW;
    vec3 front;
    vec3 back;
    vec3 uvFacing;
};

NearVertex readVertex(uint slot) {
    uvec4 a = texelFetch(nearVertices, int(2u * slot)), b = texelFetch(nearVertices, int(2u * slot + 1u));
    NearVertex v;
    v.pixel = uintBitsToFloat(a.xy);
    v.invW = uintBitsToFloat(a.z);
    v.front = unpackRgb9e5(b.x);
    v.back = unpackRgb9e5(b.y);
    v.uvFacing = vec3(uintBitsToFloat(b.zw), uintBitsToFloat(a.w));
    return v;
}

// Past the end of its row's span (col > hi), on to the first of the next rows with a pixel inside;
// at the triangle's last row, col stays past hi. The loop tests at its end behind a guard: llvmpipe
// runs a loop's body once for its SIMD row even when no lane enters it, so a loop tested at its
// start ran the row step once more than its busiest lane needed, in every pass of the pixel loop
// where a lane changed row (docs/BENCHMARKS.md). The same rows, the same pixels.
void nearNextCoveredRow(NearTriangle tri, inout int row, inout int col, inout int hi, inout NearEdge e0,
                        inout NearEdge e1, inout NearEdge e2) {
    if (col > hi && row < tri.rowHi) {
        do {
            ++row;
            e0 = nearEdgeNextRow(e0);
            e1 = nearEdgeNextRow(e1);
            e2 = nearEdgeNextRow(e2);
            col = nearSpanLow(e2, nearSpanLow(e1, nearSpanLow(e0, tri.colLo)));
            hi = nearSpanHigh(e2, nearSpanHigh(e1, nearSpanHigh(e0, tri.colHi)));
        } while (col > hi && row < tri.rowHi);
    }
}

void main() {
    uint total = nearDispatch.count;
    ivec2 size = ivec2(frame.lodScreen.zw);
    vec2 atlasSize = vec2(textureSize(atlas, 0));
    // z_clip is the near plane's distance for every point (camera.cpp's reversed, infinite projection).
    float nearPlane = frame.viewProj[3][2];
    uint stride = workStride(total);
    // The loops over draws and triangles test at their end (see the pixel loop's comment): a draw
    // has a triangle, and a lane past its draw's last triangle draws nothing. The threads' first
    // draw is their workgroup's (the cull pass adds one workgroup per listed draw) or the one their
    // SIMD row took, if any was left (near_raster.h).
    NearShare share = nearShareStart(kTakeDraws, kNearTakenRaster);
    uint item = share.item;
    if (item < total) do {
        uvec4 listed = nearList[workEntry(item, total, stride)];
        uint entry = listed.x;
        GpuDrawInstance inst = drawInstances[entry & kLodEntryIndexMask];
        uvec4 mesh = nearMeshes[listed.y];
        vec4 albedo = clumps[inst.offsets.w >> 16u].albedo; // w 1: constant albedo instead of the atlas
        uint lod = listed.y % frame.counts.w;
        bool fading = inst.pose.w > 0.0;
        bool isFadeLod = (entry & kLodFadeEntryBit) != 0u;
        uint ditherLevel = lodDitherLevel(inst.pose.w);
        uvec2 range = nearPartRange(listed.w, mesh.w / 3u); // the listed part's triangles
        uint t = range.x + share.lane;
        do {
            bool listedTriangle = t < range.y;
            uint first = mesh.z + 3u * min(t, mesh.w / 3u - 1u);
            NearVertex v0 = readVertex(listed.z + texelFetch(indices, int(first)).r);
            NearVertex v1 = readVertex(listed.z + texelFetch(indices, int(first + 1u)).r);
            NearVertex v2 = readVertex(listed.z + texelFetch(indices, int(first + 2u)).r);
            NearTriangle tri = nearSetUp(v0.pixel, v1.pixel, v2.pixel, size.x, size.y, nearListedSub(listed.w));
            if (!tri.drawn || !listedTriangle)
                continue;
            if (tri.swapped) {
                NearVertex v = v1;
                v1 = v2;
                v2 = v;
            }
            // Edge i lies opposite vertex i; its function over the area is vertex i's weight.
            NearEdge e0 = nearEdgeStart(tri.x1, tri.y1, tri.x2, tri.y2, tri.rowLo, tri.sub);
            NearEdge e1 = nearEdgeStart(tri.x2, tri.y2, tri.x0, tri.y0, tri.rowLo, tri.sub);
            NearEdge e2 = nearEdgeStart(tri.x0, tri.y0, tri.x1, tri.y1, tri.rowLo, tri.sub);
            float invArea = 1.0 / float(tri.area);
            vec3 invW = vec3(v0.invW, v1.invW, v2.invW);
            vec3 depth = nearPlane * invW;
            // The atlas's mip from the uv's change per pixel across the triangle (its screen-linear
            // part: perspective changes it little over a triangle a few pixels wide).
            vec2 duvdx = -(v0.uvFacing.xy * float(e0.s) + v1.uvFacing.xy * float(e1.s) + v2.uvFacing.xy * float(e2.s)) * invArea;
            vec2 duvdy = (v0.uvFacing.xy * float(e0.step) + v1.uvFacing.xy * float(e1.step) + v2.uvFacing.xy * float(e2.step)) * invArea;
            float mip = 0.5 * log2(max(max(dot(duvdx * atlasSize, duvdx * atlasSize), dot(duvdy * atlasSize, duvdy * atlasSize)), 1e-20));
            // One loop over the covered pixels, row by row, rather than a loop over rows around a loop over
            // each row's span: a SIMD row of threads (lavapipe's, or a GPU's warp), each on its own
            // triangle, then runs the pixel's work about as often as its busiest thread has pixels,
            // not as its longest span times its most rows. The loop tests for the next pixel at its
            // end, after the pixel's work: llvmpipe runs all of a loop's body in each pass, whatever
            // its lanes decide, so a loop that tests at its start (as `for (;;)` with a `break`
            // ahead of the work) runs the pixel's work once more, for no lane, after the last pixel
            // of every SIMD row's triangles: 1-4 ms of the pass's 32-35 in the low view on lavapipe
            // (docs/BENCHMARKS.md, "The near raster's loop tested at its end"). The same pixels, the
            // same words.
            int row = tri.rowLo, col = nearSpanLow(e2, nearSpanLow(e1, nearSpanLow(e0, tri.colLo)));
            int hi = nearSpanHigh(e2, nearSpanHigh(e1, nearSpanHigh(e0, tri.colHi)));
            nearNextCoveredRow(tri, row, col, hi, e0, e1, e2);
            do {
                // A thread whose triangle covers no pixel passes once with nothing to draw.
                bool inside = col <= hi;
                uint px = uint(tri.originX + col), py = uint(tri.originY + row);
                int at = col++;
                if (inside && (!fading || lodDitherKeepsLevel(isFadeLod, ditherLevel, px, py))) {
                    vec3 w =
                        vec3(float(nearEdgeValue(e0, at)), float(nearEdgeValue(e1, at)), float(nearEdgeValue(e2, at))) *
                        invArea;
                    vec3 pw = w * invW; // perspective-correct weights
                    pw /= pw.x + pw.y + pw.z;
                    vec3 uvFacing = pw.x * v0.uvFacing + pw.y * v1.uvFacing + pw.z * v2.uvFacing;
                    vec4 texel = albedo.w > 0.5 ? vec4(albedo.rgb, 1.0) : textureLod(atlas, uvFacing.xy, mip);
                    if (texel.a >= 0.5) {
                        bool front = uvFacing.z >= 0.0;
                        vec3 light = front ? pw.x * v0.front + pw.y * v1.front + pw.z * v2.front
                                           : pw.x * v0.back + pw.y * v1.back + pw.z * v2.back;
                        vec3 radiance = texel.rgb * light;
                        if (kLodView)
                            radiance =
                                kLodViewColors[min(lod, kLodFar)] * (front ? 1.0 : 0.6) / max(frame.skyZenith.w, 1e-6);
                        uint64_t word = packUint2x32(
                            uvec2(packRgb9e5(radiance.r, radiance.g, radiance.b), farDepthKey(dot(w, depth))));
                        atomicMin(visibility[py * uint(size.x) + px], word);
                    }
                }
                nearNextCoveredRow(tri, row, col, hi, e0, e1, e2);
            } while (col <= hi);
        } while ((t += share.width) < range.y);
    } while ((item = nearShareNext(kTakeDraws, kNearTakenRaster, share, total)) < total);
}
