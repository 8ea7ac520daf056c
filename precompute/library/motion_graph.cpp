#include "library/motion_graph.h"

#include "core/error.h"

#include <algorithm>
#include <string>
#include <vector>

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

WindResponse measureWindResponse(const MotionGraph& graph) {
    WindResponse out;
    if (graph.levelCount < 2)
        return out;
    constexpr uint32_t kInstances = 1000, kSettle = 20, kLimit = 3000;
    constexpr double kStepSeconds = 1.0 / 30.0;
    const gpu::MotionTables tables = makeMotionTables(graph);
    const uint32_t strongest = graph.levelCount - 1;
    std::vector<uint32_t> up, down;
    auto walkTo = [&](gpu::GpuMotionState& state, uint32_t level, uint32_t seed) {
        uint32_t steps = 0;
        while (graph.nodeLevel[state.frame] != level && steps < kLimit) {
            gpu::motionStep(tables, state, level, seed);
            ++steps;
        }
        out.unreached += steps == kLimit;
        return steps;
    };
    for (uint32_t i = 0; i < kInstances; ++i) {
        const uint32_t seed = i * 2654435761u;
        gpu::GpuMotionState state = initialMotionState(graph, seed, 0);
        for (uint32_t s = 0; s < kSettle; ++s)
            gpu::motionStep(tables, state, 0, seed);
        up.push_back(walkTo(state, strongest, seed));
        for (uint32_t s = 0; s < kSettle; ++s)
            gpu::motionStep(tables, state, strongest, seed);
        down.push_back(walkTo(state, 0, seed));
    }
    auto quantile = [](std::vector<uint32_t> v, double q) {
        const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
        std::nth_element(v.begin(), v.begin() + ptrdiff_t(k), v.end());
        return double(v[k]) * kStepSeconds;
    };
    out.instances = kInstances;
    out.upMedianSeconds = quantile(up, 0.5);
    out.upP95Seconds = quantile(up, 0.95);
    out.downMedianSeconds = quantile(down, 0.5);
    out.downP95Seconds = quantile(down, 0.95);
    return out;
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
