// CPU reference of shaders/cull.comp.glsl, for tests and for the CPU-driven comparison path.
#pragma once

#include "gpu_types.h"
#include "lod_select.h"

#include <cstdint>
#include <span>
#include <vector>

namespace meadow {

// The bounding sphere the cull pass tests for one instance: centred half a radius above the
// base. Returns false when the sphere lies wholly outside one of the planes.
bool instanceVisible(const gpu::GpuFrame& frame, const gpu::GpuInstance& instance);

// Signed margin of the decision: the smallest (distance to plane + radius) over the planes.
// Instances whose margin is within a few ulps of zero may be classified either way by a
// different floating-point evaluation order; tests treat those as conservative cases.
float visibilityMargin(const gpu::GpuFrame& frame, const gpu::GpuInstance& instance);

// Indices of the visible instances, ascending.
std::vector<uint32_t> cullReference(const gpu::GpuFrame& frame, std::span<const gpu::GpuInstance> instances);

// The LOD the cull pass gives a visible instance (frame.counts.w LODs, the frame's LOD
// parameters), from its coordinate of the previous frame; the same arithmetic as cull.comp.glsl.
// Whether cull.comp hands the instance's mesh LODs to the near raster (near_raster.h): the frame
// asks for it (gpu::kFrameNearRaster), the instance's sphere lies wholly in front of the near plane
// and its projected radius is at most gpu::kNearMaxRadius. Returns the subpixel grid its triangles
// snap to (gpu::nearSubpixelFor), or 0 where the mesh pass draws it.
int nearRasterReference(const gpu::GpuFrame& frame, const gpu::GpuInstance& instance);

gpu::GpuLodChoice lodReference(const gpu::GpuFrame& frame, const gpu::GpuInstance& instance, uint32_t index,
                               float previousX);

// The cull pass with levels of detail: per draw bucket (clump * LODs + LOD) its visible-list
// entries (instance index, kLodFadeEntryBit on the second draw of a crossfade), ascending.
// `lodX` holds each instance's coordinate and is updated for the visible ones, as on the GPU.
std::vector<std::vector<uint32_t>>
cullReferenceBuckets(const gpu::GpuFrame& frame, std::span<const gpu::GpuInstance> instances, std::vector<float>& lodX);

} // namespace meadow
