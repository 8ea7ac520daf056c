// The motion graph of a real simulated clump (the tiny test scene, built once): strongly
// connected, no dead end in 10^6 steps, and a fast response to a step in the wind level.
#include "motion_step.h"
#include "pipeline/build_library.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>

using namespace meadow;

namespace {

const Library& tinyLibrary() {
    static const Library library = [] {
        Scene scene = loadScene(MEADOW_SOURCE_DIR "/tests/data/scenes/tiny.json", "ci", std::nullopt);
        std::filesystem::path path = std::filesystem::temp_directory_path() / "meadow-unit-motion" / "tiny.mlib";
        buildLibrary(scene, path, true);
        return loadLibrary(path);
    }();
    return library;
}

} // namespace

TEST(MotionLibrary, GraphIsStronglyConnectedOverallAndPerLevel) {
    const MotionGraph& g = tinyLibrary().clumps[0].graph;
    EXPECT_EQ(g.levelCount, 2u);
    EXPECT_TRUE(g.stronglyConnected);
    for (uint8_t connected : g.levelStronglyConnected)
        EXPECT_TRUE(connected);
    // Independently: every live node reaches every other live node (forward search from one
    // live node, on the graph and its reverse, covers them all).
    std::vector<uint32_t> live;
    for (uint32_t i = 0; i < g.nodeCount; ++i)
        if (g.nodeAlive[i])
            live.push_back(i);
    ASSERT_FALSE(live.empty());
    auto reachable = [&](bool reverse) {
        std::vector<std::vector<uint32_t>> adjacency(g.nodeCount);
        for (uint32_t i = 0; i < g.nodeCount; ++i)
            for (uint32_t e = g.edgeStart[i]; e < g.edgeStart[i + 1]; ++e)
                (reverse ? adjacency[g.edgeTarget[e]] : adjacency[i]).push_back(reverse ? i : g.edgeTarget[e]);
        std::vector<uint8_t> seen(g.nodeCount, 0);
        std::vector<uint32_t> stack{live[0]};
        seen[live[0]] = 1;
        while (!stack.empty()) {
            uint32_t n = stack.back();
            stack.pop_back();
            for (uint32_t m : adjacency[n])
                if (!seen[m]) {
                    seen[m] = 1;
                    stack.push_back(m);
                }
        }
        return seen;
    };
    std::vector<uint8_t> forward = reachable(false), backward = reachable(true);
    for (uint32_t i : live) {
        EXPECT_TRUE(forward[i]) << i;
        EXPECT_TRUE(backward[i]) << i;
    }
}

TEST(MotionLibrary, MillionStepWalkNeverDeadEnds) {
    const MotionGraph& g = tinyLibrary().clumps[0].graph;
    gpu::MotionTables tables = makeMotionTables(g);
    gpu::GpuMotionState s = initialMotionState(g, 1234);
    uint32_t target = 0;
    for (uint32_t step = 0; step < 1000000; ++step) {
        if (step % 97 == 0)
            target = (step / 97) % g.levelCount;
        gpu::motionStep(tables, s, target, 1234);
        ASSERT_LT(s.frame, g.nodeCount) << "step " << step;
        ASSERT_TRUE(g.nodeAlive[s.frame]) << "step " << step;
    }
}

TEST(MotionLibrary, WindStepReachesStrongClipsWithinASecond) {
    const MotionGraph& g = tinyLibrary().clumps[0].graph;
    gpu::MotionTables tables = makeMotionTables(g);
    const uint32_t strong = g.levelCount - 1;
    for (uint32_t from : {0u, strong}) {
        uint32_t to = from == 0 ? strong : 0;
        std::vector<uint32_t> steps;
        for (uint32_t instance = 0; instance < 1000; ++instance) {
            gpu::GpuMotionState s = initialMotionState(g, instance, from);
            for (int warm = 0; warm < 30; ++warm)
                gpu::motionStep(tables, s, from, instance);
            uint32_t n = 0;
            while (g.nodeLevel[s.frame] != to && n < 3000) {
                gpu::motionStep(tables, s, to, instance);
                ++n;
            }
            steps.push_back(n);
        }
        std::nth_element(steps.begin(), steps.begin() + 500, steps.end());
        EXPECT_LE(steps[500], 30u) << "median frames from level " << from << " to " << to;
        std::printf("median frames from level %u to %u: %u\n", from, to, steps[500]);
    }
}

// Every graph jump of a real clump's walk starts a blend, those from a clip's last frame too
// (meadow_motion_walk measures what that does to the largest per-step vertex movement).
TEST(MotionLibrary, NoJumpGoesUnblended) {
    const MotionGraph& g = tinyLibrary().clumps[0].graph;
    const gpu::MotionTables tables = makeMotionTables(g);
    gpu::GpuMotionState state = initialMotionState(g, 99u, 0);
    uint32_t jumps = 0, fromClipEnds = 0;
    for (uint32_t step = 0; step < 100000; ++step) {
        const gpu::GpuMotionState before = state;
        gpu::motionStep(tables, state, (step / 300) % g.levelCount, 99u);
        if (state.frame == g.naturalNext[before.frame])
            continue;
        ++jumps;
        fromClipEnds += g.naturalNext[before.frame] == gpu::kMotionNoFrame;
        ASSERT_EQ(state.blendFramesLeft, g.blendFrames) << "step " << step << ": a jump from frame " << before.frame
                                                        << " to " << state.frame << " started no blend";
    }
    std::printf("[ walk     ] %u jumps in 10^5 steps, %u from a clip's last frame, all blended\n", jumps, fromClipEnds);
    EXPECT_GT(jumps, 100u);
    EXPECT_GT(fromClipEnds, 0u);
}
