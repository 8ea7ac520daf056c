// The near raster (issue 18; docs/ARCHITECTURE.md, The near raster): the mesh LODs of the clumps
// and rocks that are small enough on the screen (kNearMaxRadius) drawn by compute passes instead of lavapipe's or a
// GPU's graphics pipeline, into the far field's visibility buffer (far_splat.h's words), which the resolve pass
// composites against the meshes.
//
// The cull pass lists each LOD draw it hands over as a uvec4 (its visible-list entry, its draw
// bucket, the first of its shaded vertices in the near raster's vertex buffer, its subpixel grid), and allots it
// its mesh's vertices there; per draw bucket a uvec4 (first GpuLodVertex, vertices, first index,
// indices) says where the mesh lies (the near meshes buffer). near_vertices.comp moves and lights
// each vertex once; near_raster.comp draws the triangles.
// Its per-triangle arithmetic is here, one body compiled as C++ (the CPU reference, tests) and as
// GLSL (near_raster.comp), like far_splat.h, whose portability macros it uses.
//
// A triangle's vertices are snapped to a subpixel grid, relative to the lowest pixel of their own
// bounding box, so that every edge function is an exact 32-bit integer for boxes of up to
// kNearMaxSpan subpixels a side. The grid is 1/256 of a pixel, as lavapipe's rasteriser snaps, for
// instances whose boxes are small enough; coarser for larger ones (nearSubpixelFor), the same for
// all of an instance's triangles, so that the ones sharing an edge snap it alike. A pixel is
// covered where its centre lies inside every edge, or on an edge that is a top or a left one (the
// usual rule, so that two triangles sharing an edge cover each pixel on it once). Each row's
// covered pixels are found as a span from the three edges (NearEdge), so the shader's per-pixel
// work runs only on covered pixels.
#ifndef MEADOW_NEAR_RASTER_H
#define MEADOW_NEAR_RASTER_H

#include "far_splat.h"

#ifdef __cplusplus
#include <algorithm>
#include <bit>
#include <cmath>
namespace meadow::gpu {
using vec2 = glm::vec2;
using uvec2 = glm::uvec2;
#define MEADOW_NEAR_CONST inline constexpr uint
#define MEADOW_NEAR_FCONST inline constexpr float
#define MEADOW_NEAR_FN inline
inline int nearMinInt(int a, int b) {
    return std::min(a, b);
}
inline int nearMaxInt(int a, int b) {
    return std::max(a, b);
}
inline float nearAbs(float x) {
    return std::fabs(x);
}
inline float nearFloorF(float x) {
    return std::floor(x);
}
inline int nearLowestBit(int x) {
    return std::countr_zero(unsigned(x));
}
#else
#define MEADOW_NEAR_CONST const uint
#define MEADOW_NEAR_FCONST const float
#define MEADOW_NEAR_FN
#define nearMinInt(a, b) min(a, b)
#define nearMaxInt(a, b) max(a, b)
#define nearAbs(x) abs(x)
#define nearFloorF(x) floor(x)
#define nearLowestBit(x) findLSB(x)
#endif

// Subpixels: the largest box side whose edge functions (products of two box-relative coordinates)
// and their steps fit in 32 bits.
MEADOW_NEAR_CONST kNearMaxSpan = 1u << 14u;
// Threads per listed draw, striding over its vertices and triangles: the workgroup's width, a
// specialization constant per device (nearWidthFor in field_renderer.cpp): 64 on a GPU; on a CPU
// two SIMD rows (twice the subgroup size: 16 lanes on lavapipe at 256 bits), each taking its own
// draw (below). The picture is the same at any width.
MEADOW_NEAR_CONST kNearGroupSize = 64u;
MEADOW_NEAR_CONST kNearMaxGroups = 65535u;
// How the two passes' workgroups share the draws out (FieldScenery::nearTakeDraws):
// - Dealt in turn (a GPU's way, whose scheduler hands out workgroups as its units come free): each
//   workgroup takes slot g, then g + gl_NumWorkGroups, ... of the list in work_order.h's spread
//   order, all its threads on one draw.
// - Taken (a CPU's way): each SIMD row (subgroup) takes the next slot from a counter (NearTaken,
//   zeroed each frame), one draw per row. Lavapipe (Mesa 22.3, lp_cs_tpool.c) hands each of its
//   threads a fixed half of a dispatch's workgroups, so with the draws dealt the pass ends when the
//   costlier half does: in the low view a core idled for 3-16 ms of the near raster's 35-45
//   (docs/BENCHMARKS.md, "The near raster's draws taken from a counter"). With two rows per
//   workgroup and a workgroup per draw there are twice as many rows as draws, so either thread can
//   take any share of them; a row that finds none left passes once with nothing to draw.
// A row takes one draw, not draws until none are left, and a large draw comes in parts (below):
// llvmpipe (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS) ends every loop of a shader invocation (a SIMD
// row), silently, once all its loops together have run 65,535 passes. Rows that took draws in a
// loop lost those they took after that (20 of 565 in the default view, in a probe), and a whole LOD
// 0 draw close to the eye on one row of 4 lanes (128-bit vectors) lost pixels (docs/BENCHMARKS.md,
// "The near raster's draws taken from a counter").
MEADOW_NEAR_CONST kNearTakenVertices = 0u; // NearTaken's counters
MEADOW_NEAR_CONST kNearTakenRaster = 1u;
// A draw of an instance over 48 px (a grid of 16 or 8 to a pixel: nearSubpixelFor) is listed as
// kNearDrawParts entries, each with a run of the draw's vertices and triangles (nearPartRange), so
// that a SIMD row that takes one has a quarter of the pixels to cover: over 48 px a draw's
// triangles cover up to 30 times the pixels they do below it, more than a row of 4 lanes loops
// over in 65,535 passes. Up to kNearMaxSplitDraws draws a frame; past them a draw is listed whole
// (the near list's length is bounded: field_renderer.cpp). Below 48 px a draw's pixels are at most
// about 7,000 times its overdraw, a tenth of the limit at 4 lanes. On a GPU the parts are drawn by
// workgroups of their own, as whole draws are.
MEADOW_NEAR_CONST kNearDrawParts = 4u;
MEADOW_NEAR_CONST kNearMaxSplitDraws = 4096u;
MEADOW_NEAR_FN bool nearSplitsDraw(int sub) {
    return sub <= 16;
}
// A listed draw's fourth word: its subpixel grid (low 16 bits), which of its parts it is (8 bits)
// and how many parts it has (8 bits; 1: the whole draw).
MEADOW_NEAR_FN uint nearListedWord(int sub, uint part, uint parts) {
    return uint(sub) | part << 16u | parts << 24u;
}
MEADOW_NEAR_FN int nearListedSub(uint word) {
    return int(word & 0xffffu);
}
// The run [x, y) of a draw's `count` vertices or triangles that the listed part (`word`) covers:
// parts of count / parts, or one more; the parts together cover the draw once. A word of 0 (what
// llvmpipe's lanes past a workgroup's last thread load) gives [0, count), not a division by zero,
// whose quotient kept such lanes' loops running to llvmpipe's limit.
MEADOW_NEAR_FN uvec2 nearPartRange(uint word, uint count) {
    uint part = (word >> 16u) & 0xffu, parts = word >> 24u;
    parts += parts == 0u ? 1u : 0u;
    return uvec2(part * count / parts, (part + 1u) * count / parts);
}
// The cull pass hands an instance's LOD draws to the near raster only below this projected radius
// (px), and only when its bounding sphere lies wholly in front of the near plane, so that every
// vertex lies in front of the eye and every triangle's box within kNearMaxSpan at its instance's
// grid (nearSubpixelFor). A sphere of radius r px lies at least f / r radii from the eye (f the
// focal length in pixels: 2.4 radii at 256 px and 1280x720); seen at the picture's corners, 50
// degrees off the axis at 1280x720, it then spans at most about 1,830 px, which the 1/8 pixel grid
// holds (2,048 px).
MEADOW_NEAR_FCONST kNearMaxRadius = 256.0f;

// The subpixel grid of an instance of projected radius r px: 256 to a pixel up to 12 px (boxes up
// to 64 px), 64 up to 48 px (256 px), 16 up to 192 px (1,024 px), 8 beyond (2,048 px).
MEADOW_NEAR_FN int nearSubpixelFor(float r) {
    return r <= 12.0f ? 256 : (r <= 48.0f ? 64 : (r <= 192.0f ? 16 : 8));
}
// The near raster's vertex buffer holds this many shaded vertices (2 uvec4 each: 64 MiB); a LOD
// draw that would pass it goes to the mesh pass instead (the cull pass's atomic count decides, so
// only then does the order the instances are culled in choose which are drawn where).
MEADOW_NEAR_CONST kNearMaxVertices = 1u << 21u;

// The exponent of a grid `sub` (a power of two, as nearSubpixelFor gives): floor(a / sub) is then
// a >> nearGridShift(sub), an arithmetic shift in C++ (20) and GLSL alike. SIMD units have no
// integer division: llvmpipe divides lane by lane, six times per triangle in nearSetUp before it
// shifted (docs/BENCHMARKS.md, "The near raster's divisions as shifts").
MEADOW_NEAR_FN int nearGridShift(int sub) {
    return nearLowestBit(sub);
}

// floor(a / b) for b > 0 and |a| < 2^30, by a float division corrected to the exact quotient: SIMD
// units have no integer division (llvmpipe runs it lane by lane). The float quotient errs by at
// most 3 * 2^-24 of itself, below 200 / b, so the corrections step a few times at most. One loop
// steps either way: llvmpipe runs a loop's body once for its SIMD row even where no lane enters it,
// and nearly every quotient needs no step (docs/BENCHMARKS.md).
MEADOW_NEAR_FN int nearQuotient(int a, int b) {
    int q = int(nearFloorF(float(a) / float(b)));
    int r = a - q * b;
    while (r < 0 || r >= b) {
        int step = r < 0 ? -1 : 1;
        q += step;
        r -= step * b;
    }
    return q;
}

// A pixel coordinate (the screen's, in pixels) snapped to a grid of `sub` to the pixel.
MEADOW_NEAR_FN int nearSnap(float pixel, int sub) {
    return int(nearFloorF(pixel * float(sub) + 0.5f));
}

// One edge from vertex a to vertex b, relative to the box's origin, in subpixels; `bias` is 0 for a
// top or left edge and 1 otherwise (a pixel centre exactly on it is left out).
// E(P) = dx (Py - ay) - dy (Px - ax), positive inside a triangle wound with a positive area.
MEADOW_NEAR_FN int nearEdgeBias(int dx, int dy) {
    return (dy < 0 || (dy == 0 && dx > 0)) ? 0 : 1;
}

// The edge function at the centre of pixel (px, py) of the box (subpixel units, without the bias).
MEADOW_NEAR_FN int nearEdgeAt(int ax, int ay, int bx, int by, int px, int py, int sub) {
    int cx = px * sub + sub / 2;
    int cy = py * sub + sub / 2;
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

// One edge walked down the rows of a triangle's box. Along a row the biased edge function is
// k - s px (px from the box's origin: k at px = 0, s its decrease per pixel, the edge's rise times
// the grid); from one row to the next k grows by `step`. The pixels inside are those up to
// floor(k / s) for s > 0, from -floor(k / -s) for s < 0, all or none for s = 0. That quotient q
// and its remainder r (k = q |s| + r, 0 <= r < |s|) are carried from row to row with the whole and
// remainder parts of step / |s| (dq, dr), so a row costs additions, not a division.
struct NearEdge {
    int k, s, step;
    int q, r, dq, dr;
};

MEADOW_NEAR_FN NearEdge nearEdgeStart(int ax, int ay, int bx, int by, int row, int sub) {
    NearEdge e;
    int dx = bx - ax, dy = by - ay;
    e.k = nearEdgeAt(ax, ay, bx, by, 0, row, sub) - nearEdgeBias(dx, dy);
    e.s = dy * sub;
    e.step = dx * sub;
    int a = e.s == 0 ? 1 : (e.s < 0 ? -e.s : e.s);
    e.q = nearQuotient(e.k, a);
    e.r = e.k - e.q * a;
    e.dq = nearQuotient(e.step, a);
    e.dr = e.step - e.dq * a;
    return e;
}

MEADOW_NEAR_FN NearEdge nearEdgeNextRow(NearEdge e) {
    int a = e.s == 0 ? 1 : (e.s < 0 ? -e.s : e.s);
    e.k += e.step;
    e.q += e.dq;
    e.r += e.dr;
    if (e.r >= a) {
        e.q += 1;
        e.r -= a;
    }
    return e;
}

// The row's span [lo, hi] narrowed to the pixels inside edge e (hi = -1 when none is: rows start
// at 0 or above, so the span is then empty).
MEADOW_NEAR_FN int nearSpanLow(NearEdge e, int lo) {
    return e.s < 0 ? nearMaxInt(lo, -e.q) : lo;
}
MEADOW_NEAR_FN int nearSpanHigh(NearEdge e, int hi) {
    if (e.s > 0)
        return nearMinInt(hi, e.q);
    return (e.s == 0 && e.k < 0) ? -1 : hi;
}

// Edge e's function at pixel `col` of its current row, without the bias: twice the area of the
// triangle the pixel's centre makes with the edge, in subpixels squared.
MEADOW_NEAR_FN int nearEdgeValue(NearEdge e, int col) {
    return e.k + nearEdgeBias(e.step, e.s) - e.s * col;
}

// A triangle set up for the raster from its vertices' pixel coordinates (x right, y down, (0, 0) the
// picture's top-left corner, as the viewport maps clip space): its vertices snapped, relative to `origin` (the pixel
// whose corner lies at or below the lowest vertex), wound so that its doubled area is positive (`swapped`: vertices 1
// and 2 were exchanged for that), and the box-relative pixels whose centres it may cover, clamped to the picture.
struct NearTriangle {
    bool drawn; // false: degenerate, outside the picture or larger than kNearMaxSpan
    bool swapped;
    int sub; // subpixels to the pixel, a power of two (nearSubpixelFor)
    int originX, originY;
    int x0, y0, x1, y1, x2, y2; // subpixels from the origin
    int area;                   // twice the area, in subpixels squared
    int colLo, colHi, rowLo, rowHi;
};

MEADOW_NEAR_FN NearTriangle nearSetUp(vec2 p0, vec2 p1, vec2 p2, int width, int height, int sub) {
    NearTriangle t;
    t.drawn = false;
    t.swapped = false;
    t.sub = sub;
    t.originX = 0;
    t.originY = 0;
    t.x0 = t.y0 = t.x1 = t.y1 = t.x2 = t.y2 = 0;
    t.area = 0;
    t.colLo = t.rowLo = 0;
    t.colHi = t.rowHi = -1;
    float fx0 = p0.x, fy0 = p0.y, fx1 = p1.x, fy1 = p1.y, fx2 = p2.x, fy2 = p2.y;
    const float reach = 32768.0f; // px: far enough off the picture to skip before snapping to ints
    if (!(nearAbs(fx0) <= reach && nearAbs(fx1) <= reach && nearAbs(fx2) <= reach && nearAbs(fy0) <= reach &&
          nearAbs(fy1) <= reach && nearAbs(fy2) <= reach)) // (false for a NaN too)
        return t;
    int sx0 = nearSnap(fx0, sub), sy0 = nearSnap(fy0, sub), sx1 = nearSnap(fx1, sub), sy1 = nearSnap(fy1, sub);
    int sx2 = nearSnap(fx2, sub), sy2 = nearSnap(fy2, sub);
    int minX = nearMinInt(sx0, nearMinInt(sx1, sx2)), maxX = nearMaxInt(sx0, nearMaxInt(sx1, sx2));
    int minY = nearMinInt(sy0, nearMinInt(sy1, sy2)), maxY = nearMaxInt(sy0, nearMaxInt(sy1, sy2));
    if (maxX - minX > int(kNearMaxSpan) || maxY - minY > int(kNearMaxSpan))
        return t;
    const int shift = nearGridShift(sub);
    t.originX = minX >> shift;
    t.originY = minY >> shift;
    t.x0 = sx0 - t.originX * sub;
    t.y0 = sy0 - t.originY * sub;
    t.x1 = sx1 - t.originX * sub;
    t.y1 = sy1 - t.originY * sub;
    t.x2 = sx2 - t.originX * sub;
    t.y2 = sy2 - t.originY * sub;
    t.area = (t.x1 - t.x0) * (t.y2 - t.y0) - (t.y1 - t.y0) * (t.x2 - t.x0);
    if (t.area == 0)
        return t;
    if (t.area < 0) {
        int x = t.x1, y = t.y1;
        t.x1 = t.x2;
        t.y1 = t.y2;
        t.x2 = x;
        t.y2 = y;
        t.area = -t.area;
        t.swapped = true;
    }
    // Pixel centres (p + 1/2) within [min, max], then within the picture, relative to the origin.
    t.colLo = nearMaxInt(-((sub / 2 - (minX - t.originX * sub)) >> shift), -t.originX);
    t.colHi = nearMinInt((maxX - t.originX * sub - sub / 2) >> shift, width - 1 - t.originX);
    t.rowLo = nearMaxInt(-((sub / 2 - (minY - t.originY * sub)) >> shift), -t.originY);
    t.rowHi = nearMinInt((maxY - t.originY * sub - sub / 2) >> shift, height - 1 - t.originY);
    t.drawn = t.colLo <= t.colHi && t.rowLo <= t.rowHi;
    return t;
}

#ifdef __cplusplus
} // namespace meadow::gpu
#else
#undef nearMinInt
#undef nearMaxInt
#undef nearAbs
#undef nearFloorF
#undef nearLowestBit
#endif
#undef MEADOW_NEAR_CONST
#undef MEADOW_NEAR_FCONST
#undef MEADOW_NEAR_FN
#endif
