// The CPU-driven comparison path (`meadow bench --driver cpu`): the paper's architecture on
// today's API. Each frame the CPU steps every instance's motion graph, culls, picks LODs and
// fills the draw commands and visible lists (with a far field, also the far list and the splat
// pass's dispatch, as the cull pass would), and uploads all of it; the GPU only lights and draws
// (and splats). It runs the same functions as the compute passes' CPU references (wind_field.h,
// motion_step.h, cull_reference.h, far_splat.h), so both paths draw the same picture.
#pragma once

#include "render/field_renderer.h"

#include <memory>
#include <span>
#include <vector>

namespace meadow {

struct CpuDriver;

// Switches `renderer` to the CPU-driven path for good. `clumps` and `instances` must be those it
// was created with. Allocates host-visible staging buffers for the per-frame uploads.
void enableCpuDriver(Context& context, FieldRenderer& renderer, std::span<const FieldClump> clumps,
                     std::span<const gpu::GpuInstance> instances);

// Called by updateFrame: steps, culls and fills the staging buffers for `frame` (every byte
// counted in Context::hostBytesWritten as it is written).
void cpuDriverUpdate(Context& context, CpuDriver& driver, const gpu::GpuFrame& frame);

// Called by recordFieldFrame in place of the animate and cull passes: copies the staging buffers
// (the visible instances' draw records, draw commands, statistics, visible lists) into the
// renderer's device buffers.
void cpuDriverRecordUploads(CpuDriver& driver, const FieldRenderer& renderer, VkCommandBuffer cmd);

// The motion states the CPU keeps (the GPU's are not used on this path).
const std::vector<gpu::GpuMotionState>& cpuDriverStates(const CpuDriver& driver);

void destroyCpuDriver(Context& context, CpuDriver& driver);

} // namespace meadow
