#include "motion/graph_connectivity.h"
#include "motion/motion_graph.h"

#include "core/error.h"
#include "synthetic_motion.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>

using namespace meadow;

namespace {

constexpr uint32_t kLevels = 4;

// 4 levels x 3 clips x 125 frames = 1,500 frames of r = 12: the shape of one clump's library.
const test::SyntheticMotion& syntheticMotion() {
    static const test::SyntheticMotion motion = test::makeSyntheticMotion(kLevels, 3, 125, 12, 2024);
    return motion;
}

const MotionGraph& syntheticGraph() {
    static const MotionGraph graph = [] {
        const MotionGraph g = buildMotionGraph(syntheticMotion().q, syntheticMotion().clips, MotionGraphParams{});
        std::cout << "[ graph    ] " << g.nodeCount << " frames, " << g.removedNodes << " pruned, " << g.edgeCount
                  << " edges, " << g.transitionCount << " transitions (" << g.crossLevelTransitionCount
                  << " cross-level), " << g.forcedClipEndTransitions << " forced clip ends, "
                  << g.crossLevelFallbackPairs.size() / 2 << " fallback level pairs\n";
        return g;
    }();
    return graph;
}

// Nodes reachable from `from` over live edges that pass `useEdge` (forward or reversed): an
// independent check of what the Tarjan pruning claims.
template <class UseEdge>
std::vector<uint8_t> reachable(const MotionGraph& g, uint32_t from, bool reversed, UseEdge useEdge) {
    std::vector<std::vector<uint32_t>> adjacency(g.nodeCount);
    for (uint32_t i = 0; i < g.nodeCount; ++i)
        for (uint32_t e = g.edgeStart[i]; e < g.edgeStart[i + 1]; ++e)
            if (useEdge(i, g.edgeTarget[e])) {
                if (reversed)
                    adjacency[g.edgeTarget[e]].push_back(i);
                else
                    adjacency[i].push_back(g.edgeTarget[e]);
            }
    std::vector<uint8_t> seen(g.nodeCount, 0);
    std::vector<uint32_t> queue{from};
    seen[from] = 1;
    for (size_t head = 0; head < queue.size(); ++head)
        for (uint32_t next : adjacency[queue[head]])
            if (!seen[next]) {
                seen[next] = 1;
                queue.push_back(next);
            }
    return seen;
}

} // namespace

TEST(MotionGraph, SizesAreSensible) {
    const MotionGraph& g = syntheticGraph();
    EXPECT_EQ(g.nodeCount, 1500u);
    EXPECT_EQ(g.levelCount, kLevels);
    // Pruning drops some clip starts that no jump reaches, never most of the library.
    EXPECT_LT(g.removedNodes, g.nodeCount / 5);
    EXPECT_GT(g.transitionCount, g.nodeCount / 4);
    EXPECT_GT(g.crossLevelTransitionCount, 0u);
    EXPECT_EQ(g.edgeStart.size(), size_t(g.nodeCount) + 1);
    EXPECT_EQ(g.edgeWeight.size(), size_t(g.levelCount) * g.edgeCount);
}

TEST(MotionGraph, StronglyConnectedOverallAndPerLevel) {
    const MotionGraph& g = syntheticGraph();
    EXPECT_TRUE(g.stronglyConnected);
    uint32_t anyLive = g.nodeCount;
    for (uint32_t i = 0; i < g.nodeCount && anyLive == g.nodeCount; ++i)
        if (g.nodeAlive[i])
            anyLive = i;
    ASSERT_LT(anyLive, g.nodeCount);
    auto all = [](uint32_t, uint32_t) { return true; };
    const auto forward = reachable(g, anyLive, false, all), backward = reachable(g, anyLive, true, all);
    for (uint32_t i = 0; i < g.nodeCount; ++i) {
        ASSERT_EQ(bool(forward[i]), bool(g.nodeAlive[i])) << "node " << i;
        ASSERT_EQ(bool(backward[i]), bool(g.nodeAlive[i])) << "node " << i;
    }
    for (uint32_t level = 0; level < g.levelCount; ++level) {
        EXPECT_TRUE(g.levelStronglyConnected[level]);
        uint32_t start = g.nodeCount;
        for (uint32_t i = 0; i < g.nodeCount && start == g.nodeCount; ++i)
            if (g.nodeAlive[i] && g.nodeLevel[i] == level)
                start = i;
        ASSERT_LT(start, g.nodeCount) << "level " << level << " has no frames";
        auto inLevel = [&](uint32_t a, uint32_t b) { return g.nodeLevel[a] == level && g.nodeLevel[b] == level; };
        const auto f = reachable(g, start, false, inLevel), b = reachable(g, start, true, inLevel);
        for (uint32_t i = 0; i < g.nodeCount; ++i) {
            const bool member = g.nodeAlive[i] && g.nodeLevel[i] == level;
            ASSERT_EQ(bool(f[i]), member) << "level " << level << " node " << i;
            ASSERT_EQ(bool(b[i]), member) << "level " << level << " node " << i;
        }
    }
}

TEST(MotionGraph, EdgesAreWellFormed) {
    const MotionGraph& g = syntheticGraph();
    for (uint32_t i = 0; i < g.nodeCount; ++i) {
        const uint32_t begin = g.edgeStart[i], end = g.edgeStart[i + 1];
        if (!g.nodeAlive[i]) {
            EXPECT_EQ(begin, end) << "pruned node " << i << " keeps edges";
            continue;
        }
        ASSERT_LT(begin, end) << "live node " << i << " dead-ends";
        double sum = 0.0;
        for (uint32_t e = begin; e < end; ++e) {
            const uint32_t j = g.edgeTarget[e];
            EXPECT_TRUE(g.nodeAlive[j]) << "edge " << i << " -> pruned " << j;
            EXPECT_EQ(bool(g.edgeIsTransition[e]), j != g.naturalNext[i]);
            EXPECT_GE(g.edgeProbability[e], 0.0f);
            sum += g.edgeProbability[e];
        }
        // Tolerance: float probabilities of up to ~10 edges normalised in double.
        EXPECT_NEAR(sum, 1.0, 1e-5) << "node " << i;
        for (uint32_t level = 0; level < g.levelCount; ++level) {
            uint32_t best = 0;
            for (uint32_t e = begin; e < end; ++e) {
                const uint32_t w = g.edgeWeight[size_t(level) * g.edgeCount + e];
                EXPECT_LE(w, 65535u);
                best = std::max(best, w);
            }
            EXPECT_GT(best, 0u) << "node " << i << " has no way on toward level " << level;
            const float cost = g.futureCost[size_t(level) * g.nodeCount + i];
            EXPECT_TRUE(std::isfinite(cost));
            EXPECT_EQ(cost == 0.0f, g.nodeLevel[i] == level);
        }
    }
    // Every clip's last frame has out-edges (it has no natural one).
    for (const MotionClip& clip : syntheticMotion().clips) {
        const uint32_t last = clip.firstFrame + clip.frameCount - 1;
        EXPECT_EQ(g.naturalNext[last], gpu::kMotionNoFrame);
        if (g.nodeAlive[last]) {
            EXPECT_LT(g.edgeStart[last], g.edgeStart[last + 1]);
        }
    }
}

TEST(MotionGraph, DeterministicAcrossThreadCounts) {
    const test::SyntheticMotion motion = test::makeSyntheticMotion(kLevels, 2, 90, 8, 99);
    auto run = [&](size_t threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return buildMotionGraph(motion.q, motion.clips, MotionGraphParams{});
    };
    const MotionGraph one = run(1), two = run(2);
    EXPECT_EQ(one.edgeStart, two.edgeStart);
    EXPECT_EQ(one.edgeTarget, two.edgeTarget);
    EXPECT_EQ(one.edgeWeight, two.edgeWeight);
    EXPECT_EQ(one.nodeAlive, two.nodeAlive);
    ASSERT_EQ(one.edgeProbability.size(), two.edgeProbability.size());
    EXPECT_EQ(0, std::memcmp(one.edgeProbability.data(), two.edgeProbability.data(),
                             sizeof(float) * one.edgeProbability.size()));
    EXPECT_EQ(0, std::memcmp(one.futureCost.data(), two.futureCost.data(), sizeof(float) * one.futureCost.size()));
}

TEST(MotionGraph, StrictThresholdFallsBackToTheBestCrossLevelPairs) {
    // So strict that few pairs pass: adjacent levels must still be joined, by their best local
    // minima, and the pruned graph must stay strongly connected.
    MotionGraphParams params;
    params.thresholdScale = 0.2f;
    // So strict that level 3 keeps 7 of its 375 frames, which the live-fraction check would refuse
    // (ALevelThatKeepsTooFewFramesFailsByName); here only the joins are under test.
    params.minLiveFraction = 0.0f;
    const MotionGraph g = buildMotionGraph(syntheticMotion().q, syntheticMotion().clips, params);
    EXPECT_FALSE(g.crossLevelFallbackPairs.empty());
    for (size_t k = 0; k + 1 < g.crossLevelFallbackPairs.size(); k += 2) {
        const uint32_t a = g.crossLevelFallbackPairs[k], b = g.crossLevelFallbackPairs[k + 1];
        EXPECT_EQ(a > b ? a - b : b - a, 1u); // only adjacent levels are forced together
    }
    EXPECT_TRUE(g.stronglyConnected);
    for (uint32_t level = 0; level < g.levelCount; ++level)
        EXPECT_TRUE(g.levelStronglyConnected[level]);
}

// Two wind levels whose motion only drifts (a plant slowly bending further): no frame resembles an
// earlier one, so only the forced clip ends and the level joins make transitions.
std::vector<MotionClip> driftingClips(Eigen::MatrixXf& q) {
    constexpr int kFrames = 60;
    q.resize(2, 2 * kFrames);
    for (int t = 0; t < kFrames; ++t) {
        q.col(t) << 0.01f * float(t), 0.05f * std::sin(0.3f * float(t));
        q.col(kFrames + t) << 0.02f * float(t) + 0.3f, 0.1f * std::cos(0.5f * float(t));
    }
    return {{0, 0, kFrames}, {1, kFrames, kFrames}};
}

TEST(MotionGraph, ALevelThatKeepsTooFewFramesFailsByName) {
    Eigen::MatrixXf q;
    const std::vector<MotionClip> clips = driftingClips(q);
    MotionGraphParams params;
    params.thresholdScale = 0.0f; // nothing passes: a clip end's forced jump lands a few frames back
    try {
        buildMotionGraph(q, clips, params);
        FAIL() << "a level of drift kept its frames without transitions";
    } catch (const MotionGraphLevelError& e) {
        EXPECT_LT(e.level, 2u);
        EXPECT_NE(std::string(e.what()).find("wind level " + std::to_string(e.level)), std::string::npos) << e.what();
    }
}

TEST(MotionGraph, LoopedLevelsKeepMoreThanHalfTheirFramesAndStayJoined) {
    Eigen::MatrixXf q;
    const std::vector<MotionClip> clips = driftingClips(q);
    MotionGraphParams params;
    params.thresholdScale = 0.0f;
    params.levelLooped = {1, 1};
    const MotionGraph g = buildMotionGraph(q, clips, params);
    EXPECT_TRUE(g.stronglyConnected);
    ASSERT_EQ(g.levelLoopFrames.size(), 2u);
    for (const MotionClip& clip : clips) {
        EXPECT_TRUE(g.levelStronglyConnected[clip.level]);
        uint32_t live = 0;
        for (uint32_t f = clip.firstFrame; f < clip.firstFrame + clip.frameCount; ++f)
            live += g.nodeAlive[f];
        EXPECT_GT(live, clip.frameCount / 2) << "level " << clip.level;
        EXPECT_GT(g.levelLoopFrames[clip.level], clip.frameCount / 2);
        EXPECT_LE(g.levelLoopFrames[clip.level], live);
        // The last frame jumps back into the clip's first half.
        const uint32_t last = clip.firstFrame + clip.frameCount - 1;
        bool loops = false;
        for (uint32_t e = g.edgeStart[last]; e < g.edgeStart[last + 1]; ++e)
            loops = loops ||
                    (g.edgeTarget[e] >= clip.firstFrame && g.edgeTarget[e] < clip.firstFrame + clip.frameCount / 2);
        EXPECT_TRUE(loops) << "level " << clip.level;
    }
    // Both ways between the levels.
    bool up = false, down = false;
    for (uint32_t i = 0; i < g.nodeCount; ++i)
        for (uint32_t e = g.edgeStart[i]; e < g.edgeStart[i + 1]; ++e) {
            up = up || (g.nodeLevel[i] == 0 && g.nodeLevel[g.edgeTarget[e]] == 1);
            down = down || (g.nodeLevel[i] == 1 && g.nodeLevel[g.edgeTarget[e]] == 0);
        }
    EXPECT_TRUE(up && down);
}

TEST(MotionGraph, ARaisedLevelThresholdAdmitsMoreTransitions) {
    MotionGraphParams strict;
    strict.thresholdScale = 0.5f;
    MotionGraphParams raised = strict;
    raised.levelThresholdScale = {1.0f, 4.0f, 1.0f, 1.0f};
    const MotionGraph a = buildMotionGraph(syntheticMotion().q, syntheticMotion().clips, strict);
    const MotionGraph b = buildMotionGraph(syntheticMotion().q, syntheticMotion().clips, raised);
    auto intraTransitions = [](const MotionGraph& g, uint32_t level) {
        uint32_t n = 0;
        for (uint32_t i = 0; i < g.nodeCount; ++i)
            for (uint32_t e = g.edgeStart[i]; e < g.edgeStart[i + 1]; ++e)
                n += g.edgeIsTransition[e] && g.nodeLevel[i] == level && g.nodeLevel[g.edgeTarget[e]] == level;
        return n;
    };
    EXPECT_GT(intraTransitions(b, 1), intraTransitions(a, 1));
    EXPECT_FLOAT_EQ(b.levelThresholdScale[1], 2.0f);
    EXPECT_FLOAT_EQ(b.levelThresholdScale[0], 0.5f);
}

TEST(MotionGraph, RejectsBadInput) {
    const Eigen::MatrixXf q = Eigen::MatrixXf::Random(4, 100);
    MotionGraphParams params;
    EXPECT_THROW(buildMotionGraph(q, {{0, 0, 60}, {1, 50, 50}}, params), Error); // overlap
    EXPECT_THROW(buildMotionGraph(q, {{0, 0, 60}, {1, 60, 41}}, params), Error); // past the end
    EXPECT_THROW(buildMotionGraph(q, {{0, 0, 50}, {2, 50, 50}}, params), Error); // level 1 missing
    EXPECT_THROW(buildMotionGraph(q, {}, params), Error);
    params.window = 1;
    EXPECT_THROW(buildMotionGraph(q, {{0, 0, 100}}, params), Error);
}

TEST(StronglyConnectedComponents, SmallCases) {
    // 0 -> 1 -> 2 -> 0 is one component; 3 only enters it; 4 is isolated.
    CsrGraph graph{{0, 1, 2, 3, 4, 4}, {1, 2, 0, 0}};
    std::vector<uint8_t> keep(5, 1);
    const std::vector<uint32_t> component = stronglyConnectedComponents(graph, keep);
    EXPECT_EQ(component[0], component[1]);
    EXPECT_EQ(component[1], component[2]);
    EXPECT_NE(component[3], component[0]);
    EXPECT_NE(component[4], component[0]);
    EXPECT_EQ(keepLargestComponent(graph, keep), 2u);
    EXPECT_EQ(keep, (std::vector<uint8_t>{1, 1, 1, 0, 0}));
}

// Not an assertion on time (docs/BENCHMARKS.md): prints how long a graph of one full-preset clump
// (~2,500 frames at rank 30) takes to build, for docs/BENCHMARKS.md.
TEST(MotionGraph, BuildTimeAtFullScale) {
    const test::SyntheticMotion motion = test::makeSyntheticMotion(kLevels, 2, 313, 30, 7);
    const auto start = std::chrono::steady_clock::now();
    const MotionGraph g = buildMotionGraph(motion.q, motion.clips, MotionGraphParams{});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[ timing   ] buildMotionGraph " << g.nodeCount << " frames x r = 30: " << seconds << " s, "
              << g.edgeCount << " edges, " << g.removedNodes << " pruned\n";
    EXPECT_TRUE(g.stronglyConnected);
}
