#include "library/motion_graph.h"

#include "core/error.h"

#include <string>

namespace meadow {

gpu::MotionTables makeMotionTables(const MotionGraph& graph) {
    gpu::MotionTables tables;
    tables.edgeStart = graph.edgeStart;
    tables.edgeTarget = graph.edgeTarget;
    tables.edgeWeight = graph.edgeWeight;
    tables.naturalNext = graph.naturalNext;
    tables.edgeCount = graph.edgeCount;
    tables.levelCount = graph.levelCount;
    tables.blendFrames = graph.blendFrames;
    return tables;
}

gpu::GpuMotionState initialMotionState(const MotionGraph& graph, uint32_t instanceSeed, uint32_t level) {
    uint32_t count = 0;
    for (uint32_t i = 0; i < graph.nodeCount; ++i)
        count += graph.nodeAlive[i] && (level == kAnyLevel || graph.nodeLevel[i] == level);
    if (count == 0)
        throw Error("motion graph: no live frame of wind level " + std::to_string(level) + " to start from");
    // Counter 0xffffffff: a stream position the walk itself reaches only after 2^32 - 1 steps.
    uint32_t pick = gpu::motionRandom(instanceSeed, 0xffffffffu) % count;
    gpu::GpuMotionState state{};
    for (uint32_t i = 0; i < graph.nodeCount; ++i)
        if (graph.nodeAlive[i] && (level == kAnyLevel || graph.nodeLevel[i] == level) && pick-- == 0) {
            state.frame = i;
            break;
        }
    state.blendFrom = state.frame;
    return state;
}

} // namespace meadow
