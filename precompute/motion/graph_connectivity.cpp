#include "motion/graph_connectivity.h"

#include <algorithm>

namespace meadow {

std::vector<uint32_t> stronglyConnectedComponents(const CsrGraph& graph, const std::vector<uint8_t>& keep) {
    const uint32_t n = graph.nodeCount();
    constexpr uint32_t kUnvisited = std::numeric_limits<uint32_t>::max();
    std::vector<uint32_t> index(n, kUnvisited), lowLink(n, 0), component(n, kNoComponent);
    std::vector<uint8_t> onStack(n, 0);
    std::vector<uint32_t> tarjanStack;
    // The explicit call stack: (node, next edge to look at).
    std::vector<std::pair<uint32_t, uint32_t>> callStack;
    uint32_t nextIndex = 0, nextComponent = 0;

    for (uint32_t root = 0; root < n; ++root) {
        if (!keep[root] || index[root] != kUnvisited)
            continue;
        callStack.push_back({root, graph.start[root]});
        index[root] = lowLink[root] = nextIndex++;
        tarjanStack.push_back(root);
        onStack[root] = 1;
        while (!callStack.empty()) {
            auto& [node, edge] = callStack.back();
            if (edge < graph.start[node + 1]) {
                const uint32_t next = graph.target[edge++];
                if (!keep[next])
                    continue;
                if (index[next] == kUnvisited) {
                    index[next] = lowLink[next] = nextIndex++;
                    tarjanStack.push_back(next);
                    onStack[next] = 1;
                    callStack.push_back({next, graph.start[next]});
                } else if (onStack[next]) {
                    lowLink[node] = std::min(lowLink[node], index[next]);
                }
                continue;
            }
            const uint32_t finished = node;
            callStack.pop_back();
            if (lowLink[finished] == index[finished]) {
                uint32_t member;
                do {
                    member = tarjanStack.back();
                    tarjanStack.pop_back();
                    onStack[member] = 0;
                    component[member] = nextComponent;
                } while (member != finished);
                ++nextComponent;
            }
            if (!callStack.empty()) {
                const uint32_t parent = callStack.back().first;
                lowLink[parent] = std::min(lowLink[parent], lowLink[finished]);
            }
        }
    }
    return component;
}

uint32_t keepLargestComponent(const CsrGraph& graph, std::vector<uint8_t>& keep) {
    const std::vector<uint32_t> component = stronglyConnectedComponents(graph, keep);
    const uint32_t n = graph.nodeCount();
    std::vector<uint32_t> size, smallestNode;
    for (uint32_t i = 0; i < n; ++i) {
        if (component[i] == kNoComponent)
            continue;
        if (component[i] >= size.size()) {
            size.resize(component[i] + 1, 0);
            smallestNode.resize(component[i] + 1, n);
        }
        ++size[component[i]];
        smallestNode[component[i]] = std::min(smallestNode[component[i]], i);
    }
    if (size.empty())
        return 0;
    uint32_t best = 0;
    for (uint32_t c = 1; c < size.size(); ++c)
        if (size[c] > size[best] || (size[c] == size[best] && smallestNode[c] < smallestNode[best]))
            best = c;
    uint32_t dropped = 0;
    for (uint32_t i = 0; i < n; ++i)
        if (keep[i] && component[i] != best) {
            keep[i] = 0;
            ++dropped;
        }
    return dropped;
}

} // namespace meadow
