// What the clumps' indirect draws read, checked against the buffers they read it from: the index
// buffer, the LOD vertices the indices name (pulled by gl_VertexIndex in instance.vert) and the
// ranges of the visible list (gl_InstanceIndex). The renderer checks its draw template when it
// loads a field; tests check the instance counts the cull pass writes each frame.
#pragma once

#include "gpu_types.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace meadow {

struct DrawRangeLimits {
    std::span<const uint32_t> indices;  // the whole index buffer
    uint64_t lodVertexCount = 0;        // elements of the LOD vertex buffer
    uint64_t visibleCount = 0;          // elements of the visible list
    std::span<const uint32_t> capacity; // per draw: the most instances its visible range holds
};

// One line per violation, naming the draw (empty: every range fits). Checks, for every draw:
// indices [firstIndex, firstIndex + indexCount) inside the index buffer and whole triangles;
// every index plus vertexOffset a LOD vertex; [firstInstance, firstInstance + capacity) inside
// the visible list; instanceCount at most the capacity.
std::vector<std::string> checkDrawRanges(std::span<const gpu::GpuDrawIndexedCommand> draws,
                                         const DrawRangeLimits& limits);

} // namespace meadow
