// The order in which a compute pass's workgroups take the entries of a list the cull pass wrote
// (the near raster's draws), one body compiled as C++ (tests) and as GLSL (near_vertices.comp,
// near_raster.comp). The shaders that include it enable
// GL_EXT_shader_explicit_arithmetic_types_int64.
//
// Why: lavapipe (Mesa 22.3, lp_cs_tpool.c) splits a dispatch's workgroups between its threads in
// contiguous runs: with 2 threads, one takes the first half of the groups, the other the second.
// The cull pass appends entries in about the instances' order, which is the field's tile by tile,
// so the costly entries (the clumps nearest the eye, drawn with the most triangles and pixels)
// bunch up in one part of the list. In the default view the near raster ran on one core for 28 of
// its 46 ms (docs/BENCHMARKS.md, "One core idle"). Workgroup g, and the slots after it, take entry
// (g * stride) mod count instead: with the stride coprime with the count that is a permutation of
// the list, and with the stride near count / golden ratio, any contiguous run of slots takes
// entries spread evenly over the whole list (the three-distance theorem), so each thread's share of
// the work is about its share of the groups. On a GPU, whose scheduler hands out workgroups as its
// units come free, the order costs a multiply and a remainder per entry. The picture does not
// depend on it: the raster merges with atomicMin, in any order. The splat pass keeps the cull
// pass's order: its sets of far instances were not unbalanced, and it was slower in a spread order
// (docs/BENCHMARKS.md).
#ifndef MEADOW_WORK_ORDER_H
#define MEADOW_WORK_ORDER_H

#ifdef __cplusplus
#include <cstdint>
namespace meadow::gpu {
using uint = std::uint32_t;
using std::uint64_t;
#define MEADOW_WORK_FN inline
#else
#define MEADOW_WORK_FN
#endif

// The stride for a list of `count` entries: the first integer at or above count * 0.618 (within
// 1 / 128 of it, by shifts) that is coprime with count.
MEADOW_WORK_FN uint workStride(uint count) {
    if (count <= 2u)
        return 1u;
    uint stride = (count >> 1u) + (count >> 3u) - (count >> 7u);
    for (;;) {
        uint a = count, b = stride; // Euclid: gcd(count, stride)
        while (b != 0u) {
            uint t = a % b;
            a = b;
            b = t;
        }
        if (a == 1u)
            return stride;
        stride += 1u;
    }
}

// The entry that slot `slot` (< count) takes; `stride` is workStride(count).
MEADOW_WORK_FN uint workEntry(uint slot, uint count, uint stride) {
    return uint((uint64_t(slot) * uint64_t(stride)) % uint64_t(count));
}

#ifdef __cplusplus
} // namespace meadow::gpu
#endif
#undef MEADOW_WORK_FN
#endif
