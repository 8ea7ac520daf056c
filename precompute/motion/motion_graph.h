// The wind-indexed motion graph (DESIGN.md 2.4; Cove & James 2004, section 2.1): frames of the
// per-level simulations are nodes, natural edges play them in order, transition edges jump
// between similar frames (video textures, Schödl et al. 2000; motion graphs, Kovar et al. 2002).
// Offline, the graph is pruned to strongly connected components and every edge gets an integer
// choice weight per target wind level; the run-time walk is gpu::motionStep in
// shaders/shared/motion_step.h, which reads only the integer tables.
//
// Node ids are frame ids (columns of q): pruned frames keep their id but have no edges and no
// edge leads to them, so q needs no re-indexing and a blend partner may still show them.
#pragma once

#include "motion/frame_distance.h"
#include "motion_step.h"

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
};

struct MotionGraph {
    uint32_t nodeCount = 0;  // = frames of q
    uint32_t levelCount = 0; // wind levels, 1 + the largest clip level
    uint32_t edgeCount = 0;
    uint32_t blendFrames = 0;
    std::vector<uint8_t> nodeLevel;        // per node: its clip's wind level (0 where no clip covers it)
    std::vector<uint8_t> nodeAlive;        // per node: 1 if it survived pruning (has edges, is reachable)
    std::vector<uint32_t> naturalNext;     // per node: node + 1 inside its clip, else gpu::kMotionNoFrame
    std::vector<uint32_t> edgeStart;       // CSR, nodeCount + 1: node i's edges are [edgeStart[i], edgeStart[i + 1])
    std::vector<uint32_t> edgeTarget;      // per edge; a node's natural edge comes first, then by target
    std::vector<uint8_t> edgeIsTransition; // per edge: 0 natural (i -> i + 1), 1 transition
    std::vector<float> edgeDistance;       // per edge: D(i -> j) (0 for natural edges)
    std::vector<float> edgeProbability;    // per edge: P ∝ exp(-D / sigma), summing to 1 over each live node
    std::vector<float> futureCost;    // [level * nodeCount + node]: fewest frames until `level` plays; +inf if pruned
    std::vector<uint32_t> edgeWeight; // [level * edgeCount + edge]: 0..65535, each live node's best edge 65535

    bool stronglyConnected = false;                // the live graph as a whole
    std::vector<uint8_t> levelStronglyConnected;   // per level: its live nodes with intra-level edges
    uint32_t removedNodes = 0;                     // frames of clips dropped by pruning
    uint32_t transitionCount = 0;                  // transition edges, all levels
    uint32_t crossLevelTransitionCount = 0;        // of which join two levels
    uint32_t forcedClipEndTransitions = 0;         // clip ends given their best same-level jump regardless of threshold
    std::vector<uint32_t> crossLevelFallbackPairs; // (from, to) level pairs, flattened, that had too few
                                                   // transitions below threshold and took the best local minima
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
//     non-adjacent levels keep only genuine matches.
//  4. A clip's last frame with no same-level transition gets its best same-level jump.
//  5. Pruning to a fixed point: keep the largest SCC of the whole graph, then of each level's
//     subgraph, until nothing changes.
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

// The run-time tables as spans into graph (which must outlive the result).
gpu::MotionTables makeMotionTables(const MotionGraph& graph);

inline constexpr uint32_t kAnyLevel = 0xffffffffu;

// An instance's starting state: a live frame drawn by the instance's hash (optionally only among
// frames of `level`), no blend, counter 0. Each instance starts at its own frame (Cove & James
// 2004, section 2) so a field of copies never moves in lock step.
gpu::GpuMotionState initialMotionState(const MotionGraph& graph, uint32_t instanceSeed, uint32_t level = kAnyLevel);

} // namespace meadow
