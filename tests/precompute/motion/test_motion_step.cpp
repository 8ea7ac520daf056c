#include "motion/motion_graph.h"
#include "motion_step.h"

#include "core/random.h"
#include "synthetic_motion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

using namespace meadow;

namespace {

const MotionGraph& walkGraph() {
    static const MotionGraph graph = [] {
        const test::SyntheticMotion motion = test::makeSyntheticMotion(4, 3, 125, 12, 2024);
        return buildMotionGraph(motion.q, motion.clips, MotionGraphParams{});
    }();
    return graph;
}

bool hasEdge(const MotionGraph& g, uint32_t from, uint32_t to) {
    for (uint32_t e = g.edgeStart[from]; e < g.edgeStart[from + 1]; ++e)
        if (g.edgeTarget[e] == to)
            return true;
    return false;
}

// Steps until the instance shows a frame of `level`, at most `limit`.
uint32_t stepsUntilLevel(const MotionGraph& g, const gpu::MotionTables& tables, gpu::GpuMotionState& state,
                         uint32_t level, uint32_t seed, uint32_t limit) {
    uint32_t steps = 0;
    while (g.nodeLevel[state.frame] != level && steps < limit) {
        gpu::motionStep(tables, state, level, seed);
        ++steps;
    }
    return steps;
}

uint32_t median(std::vector<uint32_t> values) {
    std::nth_element(values.begin(), values.begin() + ptrdiff_t(values.size() / 2), values.end());
    return values[values.size() / 2];
}

} // namespace

TEST(MotionStep, HashIsTheReferencePcg) {
    // Pinned values: a GPU port must reproduce these words exactly.
    EXPECT_EQ(gpu::motionPcgHash(0u), 129708002u);
    EXPECT_EQ(gpu::motionPcgHash(1u), 2831084092u);
    EXPECT_NE(gpu::motionRandom(1u, 0u), gpu::motionRandom(0u, 1u));
}

TEST(MotionStep, FollowsOnlyPositiveWeights) {
    // Node 0 -> {1 (weight 0), 2 (weight 7)} for level 0; -> {1 (3), 2 (0)} for level 1.
    const std::vector<uint32_t> start{0, 2, 3, 4}, target{1, 2, 0, 0}, weight{0, 7, 1, 1, 3, 0, 1, 1},
        natural{1, gpu::kMotionNoFrame, gpu::kMotionNoFrame};
    gpu::MotionTables tables{start, target, weight, natural, 4, 2, 6};
    for (uint32_t seed = 0; seed < 100; ++seed) {
        gpu::GpuMotionState a{0, 0, 0, seed}, b{0, 0, 0, seed};
        gpu::motionStep(tables, a, 0, seed);
        gpu::motionStep(tables, b, 5, seed); // clamped to the last level
        EXPECT_EQ(a.frame, 2u);
        EXPECT_EQ(a.blendFramesLeft, 6u); // 0 -> 2 is a jump away from 0's natural successor 1
        EXPECT_EQ(a.blendFrom, 1u);
        EXPECT_EQ(b.frame, 1u);
        EXPECT_EQ(b.blendFramesLeft, 0u); // natural edge: no blend
        EXPECT_EQ(a.counter, seed + 1);
    }
}

TEST(MotionStep, MillionStepWalkNeverDeadEnds) {
    const MotionGraph& g = walkGraph();
    const gpu::MotionTables tables = makeMotionTables(g);
    gpu::GpuMotionState state = initialMotionState(g, 12345u);
    Random random(77);
    uint32_t level = 0, untilChange = 0, transitions = 0;
    std::vector<uint32_t> framesPerLevel(g.levelCount, 0);
    for (uint32_t step = 0; step < 1000000; ++step) {
        if (untilChange-- == 0) {
            level = uint32_t(random.next() % g.levelCount);
            untilChange = 30 + uint32_t(random.next() % 300);
        }
        const uint32_t from = state.frame;
        gpu::motionStep(tables, state, level, 12345u);
        ASSERT_LT(state.frame, g.nodeCount);
        ASSERT_TRUE(g.nodeAlive[state.frame]) << "step " << step;
        ASSERT_TRUE(hasEdge(g, from, state.frame)) << "step " << step;
        transitions += state.frame != g.naturalNext[from];
        ++framesPerLevel[g.nodeLevel[state.frame]];
    }
    std::cout << "[ walk     ] 10^6 steps, " << transitions << " jumps; frames per level:";
    for (uint32_t n : framesPerLevel) {
        std::cout << ' ' << n;
        EXPECT_GT(n, 100000u); // every level gets played while the target wanders
    }
    std::cout << '\n';
}

TEST(MotionStep, FollowsTheWindWithinOneSecond) {
    const MotionGraph& g = walkGraph();
    const gpu::MotionTables tables = makeMotionTables(g);
    constexpr uint32_t kInstances = 1000, kLimit = 3000;
    std::vector<uint32_t> upSteps, downSteps;
    for (uint32_t instance = 0; instance < kInstances; ++instance) {
        const uint32_t seed = instance * 2654435761u;
        gpu::GpuMotionState state = initialMotionState(g, seed, 0);
        // Calm air for a while, so instances are spread over calm clips and mid-blend.
        for (uint32_t s = 0; s < 20; ++s)
            gpu::motionStep(tables, state, 0, seed);
        ASSERT_EQ(g.nodeLevel[state.frame], 0u);
        upSteps.push_back(stepsUntilLevel(g, tables, state, 3, seed, kLimit));
        for (uint32_t s = 0; s < 20; ++s)
            gpu::motionStep(tables, state, 3, seed);
        downSteps.push_back(stepsUntilLevel(g, tables, state, 0, seed, kLimit));
    }
    const uint32_t up = median(upSteps), down = median(downSteps);
    std::cout << "[ wind     ] median steps calm -> strong " << up << ", strong -> calm " << down << "; worst "
              << *std::max_element(upSteps.begin(), upSteps.end()) << ", "
              << *std::max_element(downSteps.begin(), downSteps.end()) << '\n';
    // Median <= 1 s at 30 Hz (docs/BENCHMARKS.md, The numbers meadow holds itself to).
    EXPECT_LE(up, 30u);
    EXPECT_LE(down, 30u);
    EXPECT_LT(*std::max_element(upSteps.begin(), upSteps.end()), kLimit);
    EXPECT_LT(*std::max_element(downSteps.begin(), downSteps.end()), kLimit);
}

TEST(MotionStep, BlendStateCountsDownAndRestarts) {
    const MotionGraph& g = walkGraph();
    const gpu::MotionTables tables = makeMotionTables(g);
    gpu::GpuMotionState state = initialMotionState(g, 4242u);
    uint32_t blendsStarted = 0, blendsRestarted = 0, clipEndJumps = 0, heldFrames = 0;
    for (uint32_t step = 0; step < 200000; ++step) {
        const gpu::GpuMotionState before = state;
        gpu::motionStep(tables, state, (step / 500) % g.levelCount, 4242u);
        const bool jumped = state.frame != g.naturalNext[before.frame];
        const uint32_t natural = g.naturalNext[before.frame];
        if (jumped) {
            // Every jump (re)starts the blend: from where the old path would have gone, or from the
            // frame it leaves when that is its clip's last.
            ASSERT_EQ(state.blendFramesLeft, g.blendFrames);
            ASSERT_EQ(state.blendFrom, natural != gpu::kMotionNoFrame ? natural : before.frame);
            ++blendsStarted;
            blendsRestarted += before.blendFramesLeft > 1;
            clipEndJumps += natural == gpu::kMotionNoFrame;
        } else if (before.blendFramesLeft > 0) {
            // The blend counts down to its end; the old path moves on, or holds its clip's last frame.
            ASSERT_EQ(state.blendFramesLeft, before.blendFramesLeft - 1);
            const uint32_t partnerNext = g.naturalNext[before.blendFrom];
            if (state.blendFramesLeft > 0) {
                ASSERT_EQ(state.blendFrom, partnerNext != gpu::kMotionNoFrame ? partnerNext : before.blendFrom);
                heldFrames += partnerNext == gpu::kMotionNoFrame;
            }
        } else {
            ASSERT_EQ(state.blendFramesLeft, 0u);
        }
        ASSERT_LE(state.blendFramesLeft, g.blendFrames);
    }
    std::cout << "[ blend    ] " << blendsStarted << " blends, " << blendsRestarted << " restarted mid-blend, "
              << clipEndJumps << " from a clip's last frame; " << heldFrames << " steps held a clip's last frame\n";
    EXPECT_GT(blendsStarted, 1000u);
    EXPECT_GT(blendsRestarted, 0u);
    EXPECT_GT(clipEndJumps, 0u); // the walk did meet the case that once went unblended
}

TEST(MotionStep, StartFramesAreLiveAndSpread) {
    const MotionGraph& g = walkGraph();
    std::vector<uint8_t> used(g.nodeCount, 0);
    for (uint32_t seed = 0; seed < 2000; ++seed) {
        const gpu::GpuMotionState s = initialMotionState(g, seed, 2);
        ASSERT_TRUE(g.nodeAlive[s.frame]);
        ASSERT_EQ(g.nodeLevel[s.frame], 2u);
        EXPECT_EQ(s.blendFramesLeft, 0u);
        EXPECT_EQ(s.counter, 0u);
        used[s.frame] = 1;
    }
    uint32_t distinct = 0;
    for (uint8_t u : used)
        distinct += u;
    EXPECT_GT(distinct, 250u); // ~370 level-2 frames, 2,000 draws
}
