// The foundation's stand-in plant: a tuft of curved, tapering two-sided blades. It proves the
// instancing path until the iris clumps of the motion library replace it.
#pragma once

#include "gpu_types.h"

#include <cstdint>
#include <vector>

namespace meadow {

struct Mesh {
    std::vector<gpu::GpuVertex> vertices;
    std::vector<uint32_t> indices;
    float boundingRadius = 0.0f; // of the sphere centred at half this radius above the base
};

// Deterministic for a given blade count.
Mesh makeTuftMesh(uint32_t blades = 9, uint32_t segments = 5);

} // namespace meadow
