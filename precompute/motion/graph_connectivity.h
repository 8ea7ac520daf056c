// Strongly connected components of a directed graph in CSR form (Tarjan 1972), used to prune the
// motion graph so that no walk dead-ends (Kovar et al. 2002, section 3.3). Internal to
// meadow_motion; exposed for tests.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

namespace meadow {

inline constexpr uint32_t kNoComponent = std::numeric_limits<uint32_t>::max();

// A directed graph: node i's out-edges go to target[start[i] .. start[i + 1]).
struct CsrGraph {
    std::vector<uint32_t> start; // nodeCount + 1
    std::vector<uint32_t> target;
    uint32_t nodeCount() const { return uint32_t(start.size()) - 1; }
};

// Component id of every node with keep[node] != 0 (kNoComponent for the others); edges into
// dropped nodes are ignored. Iterative, so a 10^5-frame chain cannot overflow the stack.
// Deterministic: ids follow Tarjan's completion order from node 0 upwards.
std::vector<uint32_t> stronglyConnectedComponents(const CsrGraph& graph, const std::vector<uint8_t>& keep);

// keep restricted to the largest strongly connected component among the kept nodes (ties go to
// the component holding the smallest node id). Returns the number of nodes dropped.
uint32_t keepLargestComponent(const CsrGraph& graph, std::vector<uint8_t>& keep);

} // namespace meadow
