// The wind-indexed motion graph as the library keeps it and the run time walks it (Cove & James
// 2004, section 2.1): frames of the per-level simulations are nodes, natural edges play them in
// order, transition edges jump between similar frames. motion/motion_graph.h builds it offline;
// the run-time walk is gpu::motionStep in shaders/shared/motion_step.h, which reads only the
// integer tables.
//
// Node ids are frame ids: pruned frames keep their id but have no edges and no edge leads to
// them, so the motion coordinates need no re-indexing and a blend partner may still show them.
#pragma once

#include "motion_step.h"

#include <cstdint>
#include <vector>

namespace meadow {

// The library stores every table but edgeDistance, forcedClipEndTransitions and
// crossLevelFallbackPairs, which only the build's report reads.
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
    // How the build adapted each level so that it kept a usable part of its frames (a plant whose
    // motion offers few transitions): the threshold scale its transitions passed (1 when nothing
    // was adapted), and the frames of its loop, 0 where the level is not looped (its clips end with
    // a jump back into their first half; motion/motion_graph.h, step 4).
    std::vector<float> levelThresholdScale;
    std::vector<uint32_t> levelLoopFrames;
};

// The run-time tables as spans into graph (which must outlive the result).
gpu::MotionTables makeMotionTables(const MotionGraph& graph);

inline constexpr uint32_t kAnyLevel = 0xffffffffu;

// An instance's starting state: a live frame drawn by the instance's hash (optionally only among
// frames of `level`), no blend, counter 0. Each instance starts at its own frame (Cove & James
// 2004, section 2) so a field of copies never moves in lock step.
gpu::GpuMotionState initialMotionState(const MotionGraph& graph, uint32_t instanceSeed, uint32_t level = kAnyLevel);

// How fast the walk follows the wind (the ≤ 1 s target): 1000 instances walk the graph with
// motionStep, 20 steps in calm air, then toward the strongest level until they play a frame of it
// (up), 20 steps there, then back until they play a calm frame (down); at most 100 s each. The
// same numbers for the same graph, in the precompute's log and in `meadow inspect`.
struct WindResponse {
    double upMedianSeconds = 0.0, upP95Seconds = 0.0;
    double downMedianSeconds = 0.0, downP95Seconds = 0.0;
    uint32_t instances = 0, unreached = 0; // walks that hit the 100 s limit
};
WindResponse measureWindResponse(const MotionGraph& graph);

} // namespace meadow
