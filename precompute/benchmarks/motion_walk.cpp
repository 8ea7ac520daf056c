// How much a clump's vertices pop from one motion step to the next, as the run time plays them:
// walks each clump of a library 10^5 steps through the motion graph (motion_step.h, the animate
// pass's own code) with the wind level changing every 300 steps (10 s), blends the displayed
// pose as instance.vert does, and prints per clump the per-step change of velocity at LOD 0,
// x(t) - 2 x(t-1) + x(t-2), as its root mean square over the clump's vertices (a pop is a jump in
// velocity of the whole clump; fast but smooth motion has little): its 99.9th percentile and
// largest value over natural steps, over graph jumps and their blends, and at the jumps that
// started no blend.
//   meadow_motion_walk LIBRARY [STEPS]
#include "library/library.h"
#include "library/motion_graph.h"
#include "motion_step.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <glm/glm.hpp>
#include <string>
#include <tbb/parallel_for.h>
#include <vector>

using namespace meadow;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: meadow_motion_walk LIBRARY [STEPS]\n");
        return 2;
    }
    try {
        const Library lib = loadLibrary(argv[1]);
        const uint32_t steps = argc > 2 ? uint32_t(std::stoul(argv[2])) : 100000u;
        std::printf(
            "clump, steps, jumps, unblended jumps, cut blends; change of velocity, RMS over vertices (mm per step): "
            "natural (p99.9, max), at a jump or in its blend (p99.9, max), at an unblended jump (max)\n");
        for (const LibraryClump& clump : lib.clumps) {
            const MotionBasis& m = clump.motion;
            const MotionGraph& g = clump.graph;
            const uint32_t vertices = uint32_t(clump.mesh.vertices.size());
            // Every frame's displacements at LOD 0, once.
            std::vector<glm::vec3> frames(size_t(m.frames) * vertices);
            tbb::parallel_for(0u, m.frames, [&](uint32_t f) {
                for (uint32_t v = 0; v < vertices; ++v)
                    frames[size_t(f) * vertices + v] = m.displacement(v, f);
            });
            const gpu::MotionTables tables = makeMotionTables(g);
            const uint32_t seed = 12345u;
            gpu::GpuMotionState state = initialMotionState(g, seed, 0);
            std::vector<glm::vec3> shown(vertices), previous(vertices), older(vertices);
            auto display = [&](const gpu::GpuMotionState& s, std::vector<glm::vec3>& out) {
                const float w = s.blendFramesLeft > 0 ? float(s.blendFramesLeft) / float(g.blendFrames) : 0.0f;
                for (uint32_t v = 0; v < vertices; ++v) {
                    const glm::vec3 a = frames[size_t(s.frame) * vertices + v];
                    out[v] = w > 0.0f ? glm::mix(a, frames[size_t(s.blendFrom) * vertices + v], w) : a;
                }
            };
            display(state, previous);
            older = previous;
            uint32_t jumps = 0, unblended = 0, cut = 0, sinceJump = ~0u;
            float maxUnblended = 0.0f;
            std::vector<float> jumpSteps, naturalSteps;
            for (uint32_t step = 0; step < steps; ++step) {
                const gpu::GpuMotionState before = state;
                gpu::motionStep(tables, state, (step / 300u) % g.levelCount, seed);
                const bool jumped = state.frame != g.naturalNext[before.frame];
                const bool unblendedJump = jumped && state.blendFramesLeft == 0;
                if (jumped) {
                    ++jumps;
                    unblended += unblendedJump;
                    sinceJump = 0;
                } else if (sinceJump != ~0u) {
                    ++sinceJump;
                }
                cut += before.blendFramesLeft > 1 && state.blendFramesLeft == 0 && !jumped;
                display(state, shown);
                // Root mean square over the clump's vertices: a pop moves them all, while a few
                // fluttering petal vertices dominate any maximum over vertices.
                double sum = 0.0;
                for (uint32_t v = 0; v < vertices; ++v) {
                    const glm::vec3 d = shown[v] - 2.0f * previous[v] + older[v];
                    sum += double(glm::dot(d, d));
                }
                const float largest = float(std::sqrt(sum / double(vertices)));
                if (unblendedJump)
                    maxUnblended = std::max(maxUnblended, largest);
                (sinceJump <= g.blendFrames ? jumpSteps : naturalSteps).push_back(largest);
                std::swap(older, previous);
                std::swap(previous, shown);
            }
            auto p999 = [](std::vector<float>& v) {
                std::sort(v.begin(), v.end());
                return v.empty() ? 0.0f : v[size_t(0.999 * double(v.size() - 1))] * 1000.0f;
            };
            auto largestOf = [](const std::vector<float>& v) { return v.empty() ? 0.0f : v.back() * 1000.0f; };
            const float naturalP = p999(naturalSteps), jumpP = p999(jumpSteps);
            std::printf("%s, %u, %u, %u, %u; %.1f, %.1f; %.1f, %.1f; %.1f\n", clump.name.c_str(), steps, jumps,
                        unblended, cut, naturalP, largestOf(naturalSteps), jumpP, largestOf(jumpSteps),
                        maxUnblended * 1000.0f);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "meadow_motion_walk: %s\n", e.what());
        return 1;
    }
    return 0;
}
