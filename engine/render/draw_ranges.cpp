#include "render/draw_ranges.h"

namespace meadow {

std::vector<std::string> checkDrawRanges(std::span<const gpu::GpuDrawIndexedCommand> draws,
                                         const DrawRangeLimits& limits) {
    std::vector<std::string> problems;
    if (limits.capacity.size() != draws.size()) {
        problems.push_back(std::to_string(draws.size()) + " draws but " + std::to_string(limits.capacity.size()) +
                           " capacities");
        return problems;
    }
    for (size_t d = 0; d < draws.size(); ++d) {
        const gpu::GpuDrawIndexedCommand& draw = draws[d];
        const std::string name = "draw " + std::to_string(d) + ": ";
        const uint64_t indexEnd = uint64_t(draw.firstIndex) + draw.indexCount;
        if (indexEnd > limits.indices.size())
            problems.push_back(name + "indices " + std::to_string(draw.firstIndex) + ".." + std::to_string(indexEnd) +
                               " past the index buffer's " + std::to_string(limits.indices.size()));
        else if (draw.indexCount % 3 != 0)
            problems.push_back(name + std::to_string(draw.indexCount) + " indices are not whole triangles");
        else
            for (uint64_t i = draw.firstIndex; i < indexEnd; ++i) {
                const int64_t vertex = int64_t(limits.indices[i]) + draw.vertexOffset;
                if (vertex < 0 || uint64_t(vertex) >= limits.lodVertexCount) {
                    problems.push_back(name + "index " + std::to_string(i) + " names LOD vertex " +
                                       std::to_string(vertex) + " of " + std::to_string(limits.lodVertexCount));
                    break;
                }
            }
        const uint64_t visibleEnd = uint64_t(draw.firstInstance) + limits.capacity[d];
        if (visibleEnd > limits.visibleCount)
            problems.push_back(name + "visible range " + std::to_string(draw.firstInstance) + ".." +
                               std::to_string(visibleEnd) + " past the visible list's " +
                               std::to_string(limits.visibleCount));
        if (draw.instanceCount > limits.capacity[d])
            problems.push_back(name + std::to_string(draw.instanceCount) + " instances in a range of " +
                               std::to_string(limits.capacity[d]));
    }
    return problems;
}

} // namespace meadow
