// A mesh as the engine draws it: vertices in the GPU layout (gpu::GpuVertex) and a triangle list,
// with the bounding sphere the cull pass tests.
#pragma once

#include "gpu_types.h"
#include "library/motion_basis.h"

#include <cstdint>
#include <vector>

namespace meadow {

struct Mesh {
    std::vector<gpu::GpuVertex> vertices;
    std::vector<uint32_t> indices;
    float boundingRadius = 0.0f; // of the sphere centred at half this radius above the base

    // Grows boundingRadius until that sphere contains every vertex.
    void fitBoundingSphere();
};

// The mesh at motion frame `frame`: the mean pose plus the LOD's reconstructed displacement
// (x̄ + U q), with normals from the deformed triangles, oriented like the mean pose's.
Mesh meshAtFrame(const Mesh& meanPose, const MotionBasis& motion, uint32_t frame, uint32_t lod = 0);

// An 8-bit sRGB RGBA image, tightly packed (the plants' texture atlas).
struct RgbaImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;
};

// A small tuft of curved, tapering two-sided blades: a cheap mesh for tests of the draw path.
// Deterministic for a given blade count.
Mesh makeTuftMesh(uint32_t blades = 9, uint32_t segments = 5);

} // namespace meadow
