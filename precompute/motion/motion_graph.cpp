#include "motion/motion_graph.h"

#include "motion/graph_connectivity.h"

#include "core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace meadow {
namespace {

struct Candidate {
    uint32_t from = 0;
    uint32_t to = 0;
    float distance = 0.0f;
};

// A total order, so sorting gives the same sequence whatever order candidates were found in.
bool candidateBefore(const Candidate& a, const Candidate& b) {
    if (a.distance != b.distance)
        return a.distance < b.distance;
    if (a.from != b.from)
        return a.from < b.from;
    return a.to < b.to;
}

void checkParams(const MotionGraphParams& p) {
    if (p.window < 2)
        throw Error("motion graph: window must be at least 2 frames, got " + std::to_string(p.window));
    if (!(p.frameRate > 0.0f) || !(p.sigmaScale > 0.0f) || !(p.thresholdScale >= 0.0f) || !(p.costTemperature > 0.0f) ||
        !(p.velocityWeight >= 0.0f) || !(p.urgentQualityFloor > 0.0f && p.urgentQualityFloor <= 1.0f) ||
        !(p.thresholdPercentile >= 0.0f && p.thresholdPercentile <= 1.0f))
        throw Error("motion graph: frameRate, sigmaScale and costTemperature must be positive, thresholdScale and "
                    "velocityWeight non-negative, urgentQualityFloor in (0, 1], thresholdPercentile in [0, 1]");
    if (p.maxTransitionsPerLevel == 0)
        throw Error("motion graph: maxTransitionsPerLevel must be at least 1");
    for (float scale : p.levelThresholdScale)
        if (!(scale > 0.0f) || !std::isfinite(scale))
            throw Error("motion graph: every levelThresholdScale must be positive and finite");
    if (!(p.minLiveFraction >= 0.0f && p.minLiveFraction <= 0.5f))
        throw Error("motion graph: minLiveFraction must be in [0, 0.5] (a loop keeps more than half a clip)");
}

// Local minimum of D over (i +- 1, j +- 1), neighbours taken only inside the same clips (across
// a clip boundary D is not a continuation). Ties go to the first pair in row-major order, so a
// plateau yields exactly one minimum.
bool isLocalMinimum(const std::vector<float>& transition, const std::vector<uint32_t>& clipOf, size_t frames, size_t i,
                    size_t j) {
    const float value = transition[i * frames + j];
    for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj) {
            if (di == 0 && dj == 0)
                continue;
            const int64_t ni = int64_t(i) + di, nj = int64_t(j) + dj;
            if (ni < 0 || nj < 0 || ni >= int64_t(frames) || nj >= int64_t(frames))
                continue;
            if (clipOf[size_t(ni)] != clipOf[i] || clipOf[size_t(nj)] != clipOf[j])
                continue;
            const float neighbour = transition[size_t(ni) * frames + size_t(nj)];
            const bool earlier = di < 0 || (di == 0 && dj < 0);
            if (earlier ? neighbour <= value : neighbour < value)
                return false;
        }
    return true;
}

CsrGraph makeCsr(const std::vector<std::vector<uint32_t>>& adjacency) {
    CsrGraph graph;
    graph.start.assign(adjacency.size() + 1, 0);
    for (size_t i = 0; i < adjacency.size(); ++i)
        graph.start[i + 1] = graph.start[i] + uint32_t(adjacency[i].size());
    graph.target.reserve(graph.start.back());
    for (const auto& edges : adjacency)
        graph.target.insert(graph.target.end(), edges.begin(), edges.end());
    return graph;
}

// Breadth-first search on the reversed graph from every live node of `level`: the fewest steps
// from each node until a frame of that level plays.
std::vector<float> stepsToLevel(const MotionGraph& g, uint32_t level) {
    std::vector<std::vector<uint32_t>> predecessors(g.nodeCount);
    for (uint32_t i = 0; i < g.nodeCount; ++i)
        for (uint32_t e = g.edgeStart[i]; e < g.edgeStart[i + 1]; ++e)
            predecessors[g.edgeTarget[e]].push_back(i);
    std::vector<float> cost(g.nodeCount, std::numeric_limits<float>::infinity());
    std::vector<uint32_t> queue;
    for (uint32_t i = 0; i < g.nodeCount; ++i)
        if (g.nodeAlive[i] && g.nodeLevel[i] == level) {
            cost[i] = 0.0f;
            queue.push_back(i);
        }
    for (size_t head = 0; head < queue.size(); ++head) {
        const uint32_t node = queue[head];
        for (uint32_t previous : predecessors[node])
            if (std::isinf(cost[previous])) {
                cost[previous] = cost[node] + 1.0f;
                queue.push_back(previous);
            }
    }
    return cost;
}

void checkInputs(const Eigen::MatrixXf& q, const std::vector<MotionClip>& clips, const MotionGraphParams& params) {
    checkParams(params);
    if (q.cols() == 0 || q.rows() == 0)
        throw Error("motion graph: q is empty (" + std::to_string(q.rows()) + " x " + std::to_string(q.cols()) + ")");
    if (clips.empty())
        throw Error("motion graph: no motion clips");
    if (!q.allFinite())
        throw Error("motion graph: q holds NaN or infinite coordinates");
}

// The nodes, one per frame: the levels (each must have a clip), each frame's level, and the frame
// after it in its clip.
MotionGraph graphNodes(const std::vector<MotionClip>& clips, const std::vector<uint32_t>& clipOf, size_t frames,
                       const MotionGraphParams& params) {
    MotionGraph g;
    g.nodeCount = uint32_t(frames);
    g.blendFrames = params.blendFrames;
    for (const MotionClip& clip : clips)
        g.levelCount = std::max(g.levelCount, clip.level + 1);
    const uint32_t levels = g.levelCount;
    {
        std::vector<uint8_t> hasClip(levels, 0);
        for (const MotionClip& clip : clips)
            hasClip[clip.level] = 1;
        for (uint32_t l = 0; l < levels; ++l)
            if (!hasClip[l])
                throw Error("motion graph: wind level " + std::to_string(l) + " has no clip");
    }
    g.nodeLevel.assign(frames, 0);
    g.naturalNext.assign(frames, gpu::kMotionNoFrame);
    for (size_t f = 0; f < frames; ++f) {
        if (clipOf[f] == kNoClip)
            continue;
        const MotionClip& clip = clips[clipOf[f]];
        g.nodeLevel[f] = uint8_t(clip.level);
        if (f + 1 < size_t(clip.firstFrame) + clip.frameCount)
            g.naturalNext[f] = uint32_t(f + 1);
    }
    return g;
}

// Distances D(i -> j), row-major F x F: how well frame j stands in for i's successor (+inf where
// no transition may be considered).
std::vector<float> distances(const Eigen::MatrixXf& q, const std::vector<MotionClip>& clips,
                             const std::vector<uint32_t>& clipOf, const MotionGraphParams& params) {
    const Eigen::MatrixXf features = motionFeatures(q, clips, params.frameRate, params.velocityWeight);
    return transitionDistances(pairwiseSquaredDistances(features), clips, clipOf, params.window);
}

// The level statistic: a low quantile of the intra-level D. Values are gathered per row in
// parallel and concatenated in row order; nth_element then depends only on the values.
std::vector<double> levelStatistics(const MotionGraph& g, const std::vector<float>& transition,
                                    const std::vector<uint32_t>& clipOf, size_t frames,
                                    const MotionGraphParams& params) {
    const uint32_t levels = g.levelCount;
    std::vector<std::vector<float>> rowValues(frames);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, frames, 32), [&](const tbb::blocked_range<size_t>& rows) {
        for (size_t i = rows.begin(); i != rows.end(); ++i) {
            if (clipOf[i] == kNoClip)
                continue;
            for (size_t j = 0; j < frames; ++j) {
                const float value = transition[i * frames + j];
                if (std::isfinite(value) && clipOf[j] != kNoClip && g.nodeLevel[j] == g.nodeLevel[i])
                    rowValues[i].push_back(value);
            }
        }
    });
    std::vector<double> levelStatistic(levels, 0.0);
    for (uint32_t l = 0; l < levels; ++l) {
        std::vector<float> values;
        for (size_t i = 0; i < frames; ++i)
            if (g.nodeLevel[i] == l)
                values.insert(values.end(), rowValues[i].begin(), rowValues[i].end());
        if (!values.empty()) {
            const size_t at = std::min(values.size() - 1, size_t(double(values.size()) * params.thresholdPercentile));
            std::nth_element(values.begin(), values.begin() + ptrdiff_t(at), values.end());
            levelStatistic[l] = values[at];
        }
        if (!(levelStatistic[l] > 0.0))
            throw Error("motion graph: wind level " + std::to_string(l) +
                        " has no pair of distinct frames to compare (clips shorter than the window, or motionless)");
    }
    return levelStatistic;
}

// A level's own factor on the threshold (1 where the caller adapted nothing).
double levelScale(const MotionGraphParams& params, uint32_t level) {
    return level < params.levelThresholdScale.size() ? double(params.levelThresholdScale[level]) : 1.0;
}

bool levelLooped(const MotionGraphParams& params, uint32_t level) {
    return level < params.levelLooped.size() && params.levelLooped[level] != 0;
}

// The largest D of a good transition from level a to level b.
double threshold(const MotionGraphParams& params, const std::vector<double>& levelStatistic, uint32_t a, uint32_t b) {
    const double scale = a == b ? levelScale(params, a) : std::sqrt(levelScale(params, a) * levelScale(params, b));
    return params.thresholdScale * scale *
           (a == b ? levelStatistic[a] : std::sqrt(levelStatistic[a] * levelStatistic[b]));
}

// Per source frame: every local minimum of D in its row, and the transitions chosen among them.
struct Candidates {
    std::vector<std::vector<Candidate>> minima;
    std::vector<std::vector<Candidate>> chosen;
};

// Local minima per row, and the ones below threshold (the best maxTransitionsPerLevel per
// target level).
Candidates localMinima(const MotionGraph& g, const std::vector<float>& transition, const std::vector<uint32_t>& clipOf,
                       size_t frames, const std::vector<double>& levelStatistic, const MotionGraphParams& params) {
    const uint32_t levels = g.levelCount;
    Candidates candidates{std::vector<std::vector<Candidate>>(frames), std::vector<std::vector<Candidate>>(frames)};
    std::vector<std::vector<Candidate>>& minima = candidates.minima;
    std::vector<std::vector<Candidate>>& chosen = candidates.chosen;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, frames, 16), [&](const tbb::blocked_range<size_t>& rows) {
        for (size_t i = rows.begin(); i != rows.end(); ++i) {
            if (clipOf[i] == kNoClip)
                continue;
            for (size_t j = 0; j < frames; ++j)
                if (std::isfinite(transition[i * frames + j]) && isLocalMinimum(transition, clipOf, frames, i, j))
                    minima[i].push_back({uint32_t(i), uint32_t(j), transition[i * frames + j]});
            std::vector<Candidate> good;
            for (const Candidate& c : minima[i])
                if (c.distance <= threshold(params, levelStatistic, g.nodeLevel[i], g.nodeLevel[c.to]))
                    good.push_back(c);
            std::sort(good.begin(), good.end(), candidateBefore);
            std::vector<uint32_t> perLevel(levels, 0);
            for (const Candidate& c : good)
                if (perLevel[g.nodeLevel[c.to]]++ < params.maxTransitionsPerLevel)
                    chosen[i].push_back(c);
        }
    });
    return candidates;
}

// How many transitions chosen from frame i lead to `level`.
uint32_t countTo(const MotionGraph& g, const std::vector<std::vector<Candidate>>& chosen, size_t i, uint32_t level) {
    uint32_t n = 0;
    for (const Candidate& c : chosen[i])
        n += g.nodeLevel[c.to] == level;
    return n;
}

bool alreadyChosen(const std::vector<std::vector<Candidate>>& chosen, const Candidate& candidate) {
    for (const Candidate& c : chosen[candidate.from])
        if (c.to == candidate.to)
            return true;
    return false;
}

// Where each clip's loop starts (kNoFrame for clips of levels that are not looped): the frame of
// the clip's first half nearest in D to its last frame's successor. The jump last -> start is
// chosen whatever else the last frame has, so start .. last is a cycle of more than half the clip.
constexpr uint32_t kNoFrame = std::numeric_limits<uint32_t>::max();

std::vector<uint32_t> closeLoops(MotionGraph& g, std::vector<std::vector<Candidate>>& chosen,
                                 const std::vector<float>& transition, const std::vector<MotionClip>& clips,
                                 size_t frames, const MotionGraphParams& params) {
    std::vector<uint32_t> loopStart(clips.size(), kNoFrame);
    g.levelLoopFrames.assign(g.levelCount, 0);
    for (size_t c = 0; c < clips.size(); ++c) {
        const MotionClip& clip = clips[c];
        if (!levelLooped(params, clip.level))
            continue;
        const size_t last = size_t(clip.firstFrame) + clip.frameCount - 1;
        Candidate best{uint32_t(last), 0, std::numeric_limits<float>::infinity()};
        for (size_t j = clip.firstFrame; j < size_t(clip.firstFrame) + clip.frameCount / 2; ++j) {
            const float value = transition[last * frames + j];
            if (value < best.distance)
                best = {uint32_t(last), uint32_t(j), value};
        }
        if (!std::isfinite(best.distance))
            throw Error("motion graph: the clip of wind level " + std::to_string(clip.level) + " (" +
                        std::to_string(clip.frameCount) + " frames) is too short to loop (more than " +
                        std::to_string(2 * (params.window + 1)) + " frames are needed)");
        if (!alreadyChosen(chosen, best))
            chosen[last].push_back(best);
        loopStart[c] = best.to;
        g.levelLoopFrames[clip.level] += uint32_t(last - best.to + 1);
    }
    return loopStart;
}

// Whether frame f may carry a join of a looped level: inside its clip's loop, or any frame of a
// level that is not looped.
bool inLoop(const std::vector<uint32_t>& loopStart, const std::vector<uint32_t>& clipOf, size_t f) {
    return loopStart[clipOf[f]] == kNoFrame || f >= loopStart[clipOf[f]];
}

// A pair of adjacent levels of which one is looped: minCrossLevelTransitions joins from a's loop
// frames to b's, each source frame's nearest target in D, the nearest pairs first, whatever the
// threshold. Existing transitions count only where both ends lie inside the loops.
void joinLoopedPair(MotionGraph& g, std::vector<std::vector<Candidate>>& chosen, const std::vector<float>& transition,
                    const std::vector<uint32_t>& clipOf, const std::vector<uint32_t>& loopStart, size_t frames,
                    uint32_t a, uint32_t b, const MotionGraphParams& params) {
    uint32_t have = 0;
    std::vector<Candidate> pool;
    for (size_t i = 0; i < frames; ++i) {
        if (clipOf[i] == kNoClip || g.nodeLevel[i] != a || !inLoop(loopStart, clipOf, i))
            continue;
        for (const Candidate& c : chosen[i])
            have += g.nodeLevel[c.to] == b && inLoop(loopStart, clipOf, c.to);
        Candidate best{uint32_t(i), 0, std::numeric_limits<float>::infinity()};
        for (size_t j = 0; j < frames; ++j) {
            const float value = transition[i * frames + j];
            if (clipOf[j] != kNoClip && g.nodeLevel[j] == b && inLoop(loopStart, clipOf, j) && value < best.distance)
                best = {uint32_t(i), uint32_t(j), value};
        }
        if (std::isfinite(best.distance) && !alreadyChosen(chosen, best))
            pool.push_back(best);
    }
    if (have >= params.minCrossLevelTransitions)
        return;
    std::sort(pool.begin(), pool.end(), candidateBefore);
    bool added = false;
    for (const Candidate& c : pool) {
        if (have >= params.minCrossLevelTransitions)
            break;
        chosen[c.from].push_back(c);
        ++have;
        added = true;
    }
    if (added) {
        g.crossLevelFallbackPairs.push_back(a);
        g.crossLevelFallbackPairs.push_back(b);
    }
}

// Adjacent levels must be joined both ways: where too few transitions were chosen, the best
// other local minima are added (and the pair of levels recorded).
void joinAdjacentLevels(MotionGraph& g, Candidates& candidates, const std::vector<float>& transition,
                        const std::vector<uint32_t>& clipOf, const std::vector<uint32_t>& loopStart, size_t frames,
                        const MotionGraphParams& params) {
    const uint32_t levels = g.levelCount;
    const std::vector<std::vector<Candidate>>& minima = candidates.minima;
    std::vector<std::vector<Candidate>>& chosen = candidates.chosen;
    for (uint32_t a = 0; a < levels; ++a)
        for (uint32_t b : {a - 1, a + 1}) {
            if (b >= levels) // a - 1 wraps for a = 0
                continue;
            if (levelLooped(params, a) || levelLooped(params, b)) {
                joinLoopedPair(g, chosen, transition, clipOf, loopStart, frames, a, b, params);
                continue;
            }
            uint32_t have = 0;
            std::vector<Candidate> pool;
            for (size_t i = 0; i < frames; ++i) {
                if (clipOf[i] == kNoClip || g.nodeLevel[i] != a)
                    continue;
                have += countTo(g, chosen, i, b);
                for (const Candidate& c : minima[i])
                    if (g.nodeLevel[c.to] == b && clipOf[c.to] != kNoClip)
                        pool.push_back(c);
            }
            if (have >= params.minCrossLevelTransitions)
                continue;
            g.crossLevelFallbackPairs.push_back(a);
            g.crossLevelFallbackPairs.push_back(b);
            std::sort(pool.begin(), pool.end(), candidateBefore);
            for (const Candidate& c : pool) {
                if (have >= params.minCrossLevelTransitions)
                    break;
                if (countTo(g, chosen, c.from, b) >= params.maxTransitionsPerLevel || alreadyChosen(chosen, c))
                    continue;
                chosen[c.from].push_back(c);
                ++have;
            }
        }
}

// Every clip's last frame needs a way on within its level: the frame of its level nearest in D.
void continueClipEnds(MotionGraph& g, std::vector<std::vector<Candidate>>& chosen, const std::vector<float>& transition,
                      const std::vector<MotionClip>& clips, const std::vector<uint32_t>& clipOf, size_t frames) {
    for (const MotionClip& clip : clips) {
        const size_t last = size_t(clip.firstFrame) + clip.frameCount - 1;
        if (countTo(g, chosen, last, clip.level) > 0)
            continue;
        Candidate best{uint32_t(last), 0, std::numeric_limits<float>::infinity()};
        for (size_t j = 0; j < frames; ++j) {
            const float value = transition[last * frames + j];
            if (clipOf[j] != kNoClip && g.nodeLevel[j] == clip.level && value < best.distance)
                best = {uint32_t(last), uint32_t(j), value};
        }
        if (!std::isfinite(best.distance))
            throw Error("motion graph: the clip ending at frame " + std::to_string(last) + " (wind level " +
                        std::to_string(clip.level) + ") has no frame of its level to continue with");
        chosen[last].push_back(best);
        ++g.forcedClipEndTransitions;
    }
}

// Each frame's successors: its natural next frame, then its chosen transitions by target frame
// (`chosen` is sorted so); `withinLevel` keeps those to the frame's own level.
struct Adjacency {
    std::vector<std::vector<uint32_t>> whole;
    std::vector<std::vector<uint32_t>> withinLevel;
};

Adjacency adjacencyLists(const MotionGraph& g, std::vector<std::vector<Candidate>>& chosen,
                         const std::vector<uint32_t>& clipOf, size_t frames) {
    Adjacency lists{std::vector<std::vector<uint32_t>>(frames), std::vector<std::vector<uint32_t>>(frames)};
    std::vector<std::vector<uint32_t>>& adjacency = lists.whole;
    std::vector<std::vector<uint32_t>>& levelAdjacency = lists.withinLevel;
    for (size_t i = 0; i < frames; ++i) {
        if (clipOf[i] == kNoClip)
            continue;
        if (g.naturalNext[i] != gpu::kMotionNoFrame)
            adjacency[i].push_back(g.naturalNext[i]);
        std::sort(chosen[i].begin(), chosen[i].end(),
                  [](const Candidate& a, const Candidate& b) { return a.to < b.to; });
        for (const Candidate& c : chosen[i])
            adjacency[i].push_back(c.to);
        for (uint32_t j : adjacency[i])
            if (g.nodeLevel[j] == g.nodeLevel[i])
                levelAdjacency[i].push_back(j);
    }
    return lists;
}

// Prune to strongly connected components, the whole graph and each level, to a fixed point;
// records which nodes live and throws when a level lost them all.
std::vector<uint8_t> pruneToStrongComponents(MotionGraph& g, const Adjacency& lists,
                                             const std::vector<uint32_t>& clipOf, size_t frames,
                                             const MotionGraphParams& params) {
    const uint32_t levels = g.levelCount;
    const CsrGraph whole = makeCsr(lists.whole), byLevel = makeCsr(lists.withinLevel);
    std::vector<uint8_t> keep(frames, 0);
    for (size_t i = 0; i < frames; ++i)
        keep[i] = clipOf[i] != kNoClip;
    for (;;) {
        uint32_t dropped = keepLargestComponent(whole, keep);
        for (uint32_t l = 0; l < levels; ++l) {
            std::vector<uint8_t> keepLevel(frames, 0);
            for (size_t i = 0; i < frames; ++i)
                keepLevel[i] = keep[i] && g.nodeLevel[i] == l;
            dropped += keepLargestComponent(byLevel, keepLevel);
            for (size_t i = 0; i < frames; ++i)
                if (g.nodeLevel[i] == l)
                    keep[i] = keep[i] && keepLevel[i];
        }
        if (dropped == 0)
            break;
    }
    g.nodeAlive = keep;
    for (size_t i = 0; i < frames; ++i)
        g.removedNodes += clipOf[i] != kNoClip && !keep[i];
    for (uint32_t l = 0; l < levels; ++l) {
        size_t live = 0, all = 0;
        for (size_t i = 0; i < frames; ++i)
            if (clipOf[i] != kNoClip && g.nodeLevel[i] == l) {
                ++all;
                live += keep[i];
            }
        if (live == 0)
            throw MotionGraphLevelError(l, "motion graph: pruning to strongly connected components left wind level " +
                                               std::to_string(l) +
                                               " without frames (too few transitions: raise thresholdScale, loop "
                                               "the level or simulate longer)");
        if (double(live) < double(params.minLiveFraction) * double(all))
            throw MotionGraphLevelError(l, "motion graph: pruning to strongly connected components left wind level " +
                                               std::to_string(l) + " " + std::to_string(live) + " of its " +
                                               std::to_string(all) + " frames (too few transitions)");
    }
    return keep;
}

// The final CSR: live nodes, edges between live nodes, natural edge first.
void finalEdges(MotionGraph& g, const std::vector<std::vector<uint32_t>>& adjacency,
                const std::vector<std::vector<Candidate>>& chosen, const std::vector<uint8_t>& keep, size_t frames) {
    g.edgeStart.assign(frames + 1, 0);
    for (size_t i = 0; i < frames; ++i) {
        if (keep[i]) {
            for (uint32_t j : adjacency[i]) {
                if (!keep[j])
                    continue;
                const bool natural = j == g.naturalNext[i];
                float distance = 0.0f;
                if (!natural)
                    for (const Candidate& c : chosen[i])
                        if (c.to == j)
                            distance = c.distance;
                g.edgeTarget.push_back(j);
                g.edgeIsTransition.push_back(natural ? 0 : 1);
                g.edgeDistance.push_back(distance);
                g.transitionCount += natural ? 0 : 1;
                g.crossLevelTransitionCount += g.nodeLevel[j] != g.nodeLevel[i];
            }
        }
        g.edgeStart[i + 1] = uint32_t(g.edgeTarget.size());
    }
    g.edgeCount = uint32_t(g.edgeTarget.size());
}

// Probabilities (Schödl et al. 2000, eq. 2). Returns each edge's quality exp(-(D - best) / sigma),
// which the weights reuse.
std::vector<double> edgeProbabilities(MotionGraph& g, const std::vector<double>& levelStatistic, size_t frames,
                                      const MotionGraphParams& params) {
    std::vector<double> quality(g.edgeCount, 0.0);
    g.edgeProbability.assign(g.edgeCount, 0.0f);
    for (size_t i = 0; i < frames; ++i) {
        const uint32_t begin = g.edgeStart[i], end = g.edgeStart[i + 1];
        if (begin == end)
            continue;
        const double sigma = params.sigmaScale * levelStatistic[g.nodeLevel[i]];
        double best = std::numeric_limits<double>::infinity();
        for (uint32_t e = begin; e < end; ++e)
            best = std::min(best, double(g.edgeDistance[e]));
        double sum = 0.0;
        for (uint32_t e = begin; e < end; ++e) {
            // Relative to the node's best edge, so exp cannot underflow for all of them at once.
            quality[e] = std::exp(-(double(g.edgeDistance[e]) - best) / sigma);
            sum += quality[e];
        }
        for (uint32_t e = begin; e < end; ++e)
            g.edgeProbability[e] = float(quality[e] / sum);
    }
    return quality;
}

// Future costs: per level, the fewest steps from each node until a frame of that level plays.
void futureCosts(MotionGraph& g, size_t frames) {
    const uint32_t levels = g.levelCount;
    g.futureCost.resize(size_t(levels) * frames);
    for (uint32_t l = 0; l < levels; ++l) {
        const std::vector<float> cost = stepsToLevel(g, l);
        std::copy(cost.begin(), cost.end(), g.futureCost.begin() + ptrdiff_t(size_t(l) * frames));
    }
}

// The integer weights per target level: quality (floored away from the level) times a preference
// for the edges on the shortest ways to it, 65535 for each node's best edge.
void edgeWeights(MotionGraph& g, const std::vector<double>& quality, size_t frames, const MotionGraphParams& params) {
    const uint32_t levels = g.levelCount;
    g.edgeWeight.assign(size_t(levels) * g.edgeCount, 0);
    std::vector<double> raw;
    for (uint32_t l = 0; l < levels; ++l) {
        const float* cost = g.futureCost.data() + size_t(l) * frames;
        for (size_t i = 0; i < frames; ++i) {
            const uint32_t begin = g.edgeStart[i], end = g.edgeStart[i + 1];
            if (begin == end)
                continue;
            const bool urgent = cost[i] > 0.0f;
            double bestCost = std::numeric_limits<double>::infinity();
            for (uint32_t e = begin; e < end; ++e)
                bestCost = std::min(bestCost, 1.0 + double(cost[g.edgeTarget[e]]));
            raw.assign(end - begin, 0.0);
            double maxRaw = 0.0;
            for (uint32_t e = begin; e < end; ++e) {
                const double q = urgent ? std::max(quality[e], double(params.urgentQualityFloor)) : quality[e];
                const double extra = 1.0 + double(cost[g.edgeTarget[e]]) - bestCost;
                raw[e - begin] = q * std::exp(-extra / params.costTemperature);
                maxRaw = std::max(maxRaw, raw[e - begin]);
            }
            for (uint32_t e = begin; e < end; ++e)
                g.edgeWeight[size_t(l) * g.edgeCount + e] = uint32_t(std::lround(65535.0 * raw[e - begin] / maxRaw));
        }
    }
}

// Connectivity as recorded facts (pruning guarantees them; tests check them independently).
void recordConnectivity(MotionGraph& g, const std::vector<uint8_t>& keep, size_t frames) {
    const uint32_t levels = g.levelCount;
    CsrGraph live{g.edgeStart, g.edgeTarget};
    std::vector<uint8_t> check = keep;
    g.stronglyConnected = keepLargestComponent(live, check) == 0;
    std::vector<std::vector<uint32_t>> intra(frames);
    for (size_t i = 0; i < frames; ++i)
        for (uint32_t e = g.edgeStart[i]; e < g.edgeStart[i + 1]; ++e)
            if (g.nodeLevel[g.edgeTarget[e]] == g.nodeLevel[i])
                intra[i].push_back(g.edgeTarget[e]);
    const CsrGraph intraGraph = makeCsr(intra);
    g.levelStronglyConnected.assign(levels, 0);
    for (uint32_t l = 0; l < levels; ++l) {
        std::vector<uint8_t> keepLevel(frames, 0);
        for (size_t i = 0; i < frames; ++i)
            keepLevel[i] = keep[i] && g.nodeLevel[i] == l;
        g.levelStronglyConnected[l] = keepLargestComponent(intraGraph, keepLevel) == 0;
    }
}

} // namespace

MotionGraph buildMotionGraph(const Eigen::MatrixXf& q, const std::vector<MotionClip>& clips,
                             const MotionGraphParams& params) {
    checkInputs(q, clips, params);
    const size_t frames = size_t(q.cols());
    const std::vector<uint32_t> clipOf = clipOfFrames(clips, uint32_t(frames));
    MotionGraph g = graphNodes(clips, clipOf, frames, params);
    g.levelThresholdScale.assign(g.levelCount, 1.0f);
    for (uint32_t l = 0; l < g.levelCount; ++l)
        g.levelThresholdScale[l] = params.thresholdScale * float(levelScale(params, l));

    const std::vector<float> transition = distances(q, clips, clipOf, params);
    const std::vector<double> levelStatistic = levelStatistics(g, transition, clipOf, frames, params);
    Candidates candidates = localMinima(g, transition, clipOf, frames, levelStatistic, params);
    const std::vector<uint32_t> loopStart = closeLoops(g, candidates.chosen, transition, clips, frames, params);
    joinAdjacentLevels(g, candidates, transition, clipOf, loopStart, frames, params);
    continueClipEnds(g, candidates.chosen, transition, clips, clipOf, frames);

    const Adjacency adjacency = adjacencyLists(g, candidates.chosen, clipOf, frames);
    const std::vector<uint8_t> keep = pruneToStrongComponents(g, adjacency, clipOf, frames, params);
    finalEdges(g, adjacency.whole, candidates.chosen, keep, frames);

    const std::vector<double> quality = edgeProbabilities(g, levelStatistic, frames, params);
    futureCosts(g, frames);
    edgeWeights(g, quality, frames, params);
    recordConnectivity(g, keep, frames);
    return g;
}

} // namespace meadow
