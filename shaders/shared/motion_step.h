// The run-time motion-graph step (docs/ARCHITECTURE.md, Motion; The run time): one function body,
// compiled as C++ for the CPU reference and as GLSL for the animate pass, so the two agree bit for
// bit. Everything here is integer arithmetic: the offline build (precompute/motion/motion_graph.h)
// turns the transition probabilities and future costs into integer choice weights, so the GPU never
// evaluates exp() and no float rounding can make the CPU and GPU walks diverge.
//
// Walks follow video textures (Schödl et al. 2000) over a motion graph (Kovar et al. 2002):
// a node is a frame of reduced coordinates q, natural edges play i -> i+1, transition edges
// jump to a similar frame. Cove & James 2004 index the graph by wind level; here the choice
// among a node's edges uses the weights of the instance's target wind level, which prefer edges
// that lead toward that level's frames.
//
// Tables (node = frame index into q; edges in CSR order):
//   edgeStart[node]          first edge of node; node's edges are [edgeStart[node], edgeStart[node + 1])
//   edgeTarget[edge]         the frame the edge leads to
//   edgeWeight[level, edge]  integer choice weight (0..65535) of edge when heading for `level`
//   naturalNext[frame]       frame + 1 inside the same simulated clip, kMotionNoFrame at a clip's end
// An edge is a transition exactly when its target is not naturalNext[node].
//
// Usage from C++:
//     #include "motion_step.h"
//     gpu::MotionTables tables = makeMotionTables(graph);      // precompute/motion/motion_graph.h
//     gpu::GpuMotionState s = initialMotionState(graph, seed); // random start frame
//     gpu::motionStep(tables, s, targetLevel, seed);           // once per 1/30 s
//
// Usage from GLSL: before including, define the table accessors (any storage layout will do):
//     uint motionEdgeStart(uint node);
//     uint motionEdgeTarget(uint edge);
//     uint motionEdgeWeight(uint level, uint edge);
//     uint motionNaturalNext(uint frame);
//     uint motionLevelCount();
//     uint motionBlendFrames();
// then `#include "motion_step.h"` and call `motionStep(state, targetLevel, instanceSeed);`.
#ifndef MEADOW_MOTION_STEP_H
#define MEADOW_MOTION_STEP_H

#include "gpu_types.h" // GpuMotionState

#ifdef __cplusplus
#include <cstdint>
#include <span>
namespace meadow::gpu {
using uint = std::uint32_t;
#define MEADOW_MOTION_CONST inline constexpr uint
#define MEADOW_MOTION_FN inline
#define MEADOW_MOTION_INOUT(T) T&
#define MEADOW_MOTION_TABLES_PARAM const MotionTables &tables,
#define MEADOW_MOTION_TABLES tables.
#else
#define MEADOW_MOTION_CONST const uint
#define MEADOW_MOTION_FN
#define MEADOW_MOTION_INOUT(T) inout T
#define MEADOW_MOTION_TABLES_PARAM
#define MEADOW_MOTION_TABLES
#endif

// naturalNext of a clip's last frame: there is no frame to continue with.
MEADOW_MOTION_CONST kMotionNoFrame = 0xffffffffu;

#ifdef __cplusplus
static_assert(sizeof(GpuMotionState) == 16, "GpuMotionState must stay four tightly packed uints");

// The CPU side's view of the tables, with the same accessor names the GLSL side defines.
// Spans do not own: the MotionGraph (or a loaded library) must outlive the view.
struct MotionTables {
    std::span<const uint> edgeStart;   // nodeCount + 1
    std::span<const uint> edgeTarget;  // edgeCount
    std::span<const uint> edgeWeight;  // levelCount * edgeCount, level-major
    std::span<const uint> naturalNext; // nodeCount
    uint edgeCount = 0;
    uint levelCount = 0;
    uint blendFrames = 0;

    uint motionEdgeStart(uint node) const { return edgeStart[node]; }
    uint motionEdgeTarget(uint edge) const { return edgeTarget[edge]; }
    uint motionEdgeWeight(uint level, uint edge) const { return edgeWeight[level * edgeCount + edge]; }
    uint motionNaturalNext(uint frame) const { return naturalNext[frame]; }
    uint motionLevelCount() const { return levelCount; }
    uint motionBlendFrames() const { return blendFrames; }
};
#endif

// PCG hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering"): a counter-based
// generator, so an instance's n-th random number needs no stored generator state.
MEADOW_MOTION_FN uint motionPcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The random number of an instance's `counter`-th step. Hashing the seed first decorrelates
// instances whose seeds differ by the same amount as their counters.
MEADOW_MOTION_FN uint motionRandom(uint instanceSeed, uint counter) {
    return motionPcgHash(counter + motionPcgHash(instanceSeed));
}

// Advances one motion frame (1/30 s). targetLevel is the wind level at the instance (clamped to
// the last level). Picks one of the frame's edges with probability weight / sum of weights for
// targetLevel; on every transition the old path keeps playing as blendFrom for blendFrames steps
// while its weight fades. Where the old path has no next frame (a jump from a clip's last frame,
// or its clip ends mid-blend) it holds its last frame while the weight fades, so no jump pops.
MEADOW_MOTION_FN void motionStep(MEADOW_MOTION_TABLES_PARAM MEADOW_MOTION_INOUT(GpuMotionState) state, uint targetLevel,
                                 uint instanceSeed) {
    uint levelCount = MEADOW_MOTION_TABLES motionLevelCount();
    uint level = targetLevel < levelCount ? targetLevel : levelCount - 1u;
    uint node = state.frame;
    uint begin = MEADOW_MOTION_TABLES motionEdgeStart(node);
    uint end = MEADOW_MOTION_TABLES motionEdgeStart(node + 1u);

    uint total = 0u;
    for (uint e = begin; e < end; ++e)
        total += MEADOW_MOTION_TABLES motionEdgeWeight(level, e);

    // The offline build guarantees total > 0 for every live node and level; the guard only keeps
    // a corrupt table from dividing by zero (the frame then holds still).
    uint next = node;
    if (total > 0u) {
        uint ticket = motionRandom(instanceSeed, state.counter) % total;
        uint accumulated = 0u;
        for (uint e = begin; e < end; ++e) {
            accumulated += MEADOW_MOTION_TABLES motionEdgeWeight(level, e);
            if (ticket < accumulated) {
                next = MEADOW_MOTION_TABLES motionEdgeTarget(e);
                break;
            }
        }
    }

    // The old path of a running blend moves on with its own clip, or holds its last frame.
    if (state.blendFramesLeft > 0u) {
        uint continued = MEADOW_MOTION_TABLES motionNaturalNext(state.blendFrom);
        if (continued != kMotionNoFrame)
            state.blendFrom = continued;
        state.blendFramesLeft -= 1u;
    }

    // A jump starts a new blend from where the current path would have gone (Kovar et al. 2002
    // blend across the transition window), or from the frame it leaves when that ends its clip;
    // a newer jump replaces an older blend.
    uint natural = MEADOW_MOTION_TABLES motionNaturalNext(node);
    if (next != natural && next != node) {
        state.blendFrom = natural != kMotionNoFrame ? natural : node;
        state.blendFramesLeft = MEADOW_MOTION_TABLES motionBlendFrames();
    }

    state.frame = next;
    state.counter += 1u;
}

#ifdef __cplusplus
} // namespace meadow::gpu
#endif
#undef MEADOW_MOTION_CONST
#undef MEADOW_MOTION_FN
#undef MEADOW_MOTION_INOUT
#undef MEADOW_MOTION_TABLES_PARAM
#undef MEADOW_MOTION_TABLES
#endif
