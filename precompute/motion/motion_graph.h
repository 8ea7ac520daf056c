// The wind-indexed motion graph (docs/ARCHITECTURE.md, Motion; Cove & James 2004, section 2.1):
// frames of the per-level simulations are nodes, natural edges play them in order, transition edges
// jump between similar frames (video textures, Schödl et al. 2000; motion graphs, Kovar et al.
// 2002). Offline, the graph is pruned to strongly connected components and every edge gets an
// integer choice weight per target wind level; the run-time walk is gpu::motionStep in
// shaders/shared/motion_step.h, which reads only the integer tables.
//
// Node ids are frame ids (columns of q): pruned frames keep their id but have no edges and no
// edge leads to them, so q needs no re-indexing and a blend partner may still show them.
#pragma once

#include "core/error.h"
#include "library/motion_graph.h"
#include "motion/frame_distance.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace meadow {

struct MotionGraphParams {
    uint32_t window = 6;                     // frames compared around a transition (even; Schödl's 2m taps)
    float velocityWeight = 0.1f;             // seconds: weight of dq/dt against q in the frame distance
    float thresholdPercentile = 0.05f;       // the level statistic s: this quantile of D over the level's frame pairs
    float thresholdScale = 1.0f;             // transitions need D below this times s
    float sigmaScale = 0.25f;                // sigma of P ∝ exp(-D / sigma), times s
    uint32_t maxTransitionsPerLevel = 4;     // per node and target level, the lowest D kept
    uint32_t minCrossLevelTransitions = 24;  // per ordered pair of adjacent levels, see buildMotionGraph
    float costTemperature = 0.5f;            // frames: how sharply edge weights prefer shorter ways to the target level
    float urgentQualityFloor = 1.0f / 16.0f; // away from the target level, a jump's relative P counts as at least this
    uint32_t blendFrames = 6;                // run-time blend length after a jump
    float frameRate = 30.0f;                 // frames per second of the simulation
    // Per-level adaptation (empty: none). levelThresholdScale multiplies thresholdScale for the
    // level's transitions (a cross-level pair takes the geometric mean of both). A looped level's
    // clips end with a forced jump back into their first half (step 4), and its joins to adjacent
    // levels are chosen inside the loops (step 3): see buildMotionGraph.
    std::vector<float> levelThresholdScale;
    std::vector<uint8_t> levelLooped;
    float minLiveFraction = 0.25f; // a level keeping fewer of its frames than this fails (step 5)
};

// What buildMotionGraph throws when a level fails step 5: pruning left it without frames, or with
// fewer than minLiveFraction of them. The caller may adapt that level and build again.
class MotionGraphLevelError : public Error {
  public:
    MotionGraphLevelError(uint32_t failedLevel, const std::string& message) : Error(message), level(failedLevel) {}
    uint32_t level;
};

// Builds the graph from reduced coordinates q (r x F, one column per frame) and the clips that
// cut those frames into per-level simulations. Steps:
//  1. D(i -> j) over a window of q and dq/dt (frame_distance.h).
//  2. Candidates: local minima of D over (i +- 1, j +- 1) (Kovar et al.), below thresholdScale
//     times a level statistic s: the thresholdPercentile quantile of D within the source level
//     for intra-level pairs, the geometric mean of both levels' s for cross-level pairs. A
//     quantile rather than the mean: with tens of reduced coordinates distances concentrate, so
//     a fixed fraction of the mean admits either nothing or everything depending on the data,
//     while a low quantile keeps the same share of the best matches. At most
//     maxTransitionsPerLevel per node and target level, lowest D first.
//  3. Adjacent levels must connect for the wind to be followed: an ordered pair (a, a +- 1) with
//     fewer than minCrossLevelTransitions takes its best local minima regardless of threshold
//     (recorded in crossLevelFallbackPairs; the run-time blend hides the larger jump). Pairs of
//     non-adjacent levels keep only genuine matches. Where either level is looped, the pair takes
//     minCrossLevelTransitions joins whatever the threshold, each source frame's best target, with
//     sources and targets inside the loops (below), so the levels stay joined both ways.
//  4. A clip's last frame with no same-level transition gets its best same-level jump. A looped
//     level's clips end with a jump to the frame of their first half nearest in D, whatever
//     other transitions the last frame has: that frame and everything after it form one cycle,
//     more than half the clip (the loop), which the run time blends over like any jump.
//  5. Pruning to a fixed point: keep the largest SCC of the whole graph, then of each level's
//     subgraph, until nothing changes. A level left with fewer than minLiveFraction of its frames
//     throws MotionGraphLevelError. With every level looped, the loops and their joins are
//     strongly connected by construction, so pruning keeps every loop and no level fails.
//  6. P per node (sigma = sigmaScale * s of the node's level); futureCost[L] by breadth-first search from L's nodes on
//  the reversed graph.
//     Weights for level L: with c(e) = 1 + futureCost[L](target) and Q(e) = P(e) / max P at the
//     node, w ∝ Q(e) * exp(-(c(e) - min c) / costTemperature). At a node of level L this is a
//     video texture of L (P decides, leaving L costs). At a node of another level the plant is in
//     the wrong wind: Q is raised to at least urgentQualityFloor so that a sound but less likely
//     jump toward L is not starved by the natural edge (every jump passed the threshold anyway).
//     Weights are scaled so each node's best edge gets 65535: positive for every level.
// Deterministic: the same inputs give the same bits for any TBB thread count. Throws
// meadow::Error on bad input (clips, parameters) or if pruning empties a level.
MotionGraph buildMotionGraph(const Eigen::MatrixXf& q, const std::vector<MotionClip>& clips,
                             const MotionGraphParams& params);

} // namespace meadow
