// What the field renderer's buffers hold, packed on the CPU once, when a field is loaded: every
// clump's LOD vertices, indices, motion rows and graph, transfer and light layout in shared
// buffers (gpu::GpuClump says where each clump's lie), one indirect draw per (clump, LOD) with
// the range of the visible list it fills, each instance's first motion state, the rectangle of
// the ground light map and the sky day. field_renderer.cpp uploads what these return.
#pragma once

#include "gpu_types.h"
#include "library/sky_day.h"
#include "render/field_renderer.h"

#include <cstdint>
#include <span>
#include <vector>
#include <vulkan/vulkan.h>

namespace meadow {

struct FieldPacking {
    std::vector<gpu::GpuClump> clumps;
    std::vector<gpu::GpuLodVertex> lodVertices;    // every clump's LODs, LOD by LOD
    std::vector<uint32_t> indices;                 // each LOD's triangles into its own vertices
    std::vector<float> motionData;                 // per moving clump: its basis rows, then its coordinates
    std::vector<uint32_t> motionGraph;             // per clump: edge starts, targets, weights, natural successors
    std::vector<float> transfer;                   // vec4s: vertex transfer with gradients, ground grid transfer
    uint64_t lightVec4s = 0;                       // the vertex light buffer's size in uvec4s
    std::vector<uint32_t> lightVertices;           // per clump: vertices (light.comp's threads)
    std::vector<uint32_t> lightGroundPoints;       // per clump: ground grid points (its ground pipeline's)
    std::vector<gpu::GpuDrawIndexedCommand> draws; // per draw bucket (clump-major), instance counts 0
    std::vector<uint32_t> meshTriangles;           // per draw bucket
    std::vector<uint32_t> meshVertices;            // per draw bucket: its GpuLodVertex from draws' vertexOffset
    std::vector<uint32_t> drawCapacity;            // per draw bucket: the instances its visible range holds
    uint32_t visibleCount = 0;                     // the visible list's length: every bucket's range
    std::vector<gpu::GpuMotionState> states;       // per instance: where its walk starts
    std::vector<gpu::GpuFarSample> farSamples;     // per clump its far-field samples (GpuClump::far)
    std::vector<gpu::GpuFarMotion> farMotion;      // per GpuLodVertex, set for the last LODs' (far samples follow)
};

// Throws meadow::Error naming "field clump <index>" for a clump the renderer cannot draw: no
// vertices, the wrong number of LODs, indices out of range, motion without a graph, transfer or
// a ground grid of the wrong size, an empty yaw range, far-field samples that follow a vertex the
// last LOD does not keep or cover no surface.
void checkFieldClump(const FieldClump& clump, size_t index, uint32_t lodCount);

// Packs the clumps (lodCount LODs each) and, for the instances, their first motion states and
// the draws' ranges of the visible list. Throws meadow::Error for an instance naming a clump
// that is not there and for clumps whose light or motion data would pass 2 GiB.
FieldPacking packField(std::span<const FieldClump> clumps, std::span<const gpu::GpuInstance> instances,
                       uint32_t lodCount);

// The atlas as the renderer samples it (VK_FORMAT_R16G16B16A16_SFLOAT): each 8-bit sRGB colour
// channel decoded to linear, each alpha to [0, 1], as half floats. Filtering then needs no decode
// per texel: llvmpipe decodes each of a trilinear sample's eight texels of an 8-bit sRGB format
// before filtering (docs/BENCHMARKS.md, "The atlas stored linear").
std::vector<uint16_t> packAtlas(const RgbaImage& atlas);

// The sky day for the skyData buffer: per frame its SH, sun and backdrop (gpu::kSkyFrameHeaderFloats
// then the image). Throws meadow::Error for a frame of the wrong size.
size_t skyFrameFloats(const sky::SkyDay& day);
std::vector<float> packSkyDay(const sky::SkyDay& day);

} // namespace meadow
