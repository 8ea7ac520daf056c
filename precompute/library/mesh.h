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

// An 8-bit sRGB-encoded channel (the atlas's texels) to linear, 0..1.
float srgbToLinear(uint8_t value);
// Linear 0..1 (clamped) to an 8-bit sRGB-encoded channel, rounded to nearest.
uint8_t linearToSrgb(float linear);

// The plants' atlas is laid out in cells whose sides are whole multiples of 1 / kAtlasGrid of its
// side, each part's texture painted to its cell's edge and used 1 / 128 of the side inside it
// (plants/atlas.cpp). Its mipmaps, 2 x 2 boxes of a power-of-two image, keep the cells apart while
// a grid unit is 2 texels or more; trilinear filtering stays inside a part while the inset is half a
// texel: up to the level where a unit is 8 texels. The run time reads no coarser level
// (atlasMaxLod): coarser ones mix the violet falls, the orange beards and the green leaves.
inline constexpr uint32_t kAtlasGrid = 8;
inline float atlasMaxLod(uint32_t width) {
    uint32_t level = 0;
    while ((width >> (level + 1)) >= kAtlasGrid * 8)
        ++level;
    return float(level);
}

// A small tuft of curved, tapering two-sided blades: a cheap mesh for tests of the draw path.
// Deterministic for a given blade count.
Mesh makeTuftMesh(uint32_t blades = 9, uint32_t segments = 5);

} // namespace meadow
