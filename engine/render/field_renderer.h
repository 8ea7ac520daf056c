// Draws a field of instances the GPU-driven way: per frame the CPU writes one uniform block;
// a compute pass culls the instances into a compacted visible list and the instanceCount of an
// indirect draw; the draw reads both; a compute pass tonemaps the result.
//
// Per frame: fill (reset counters) -> cull.comp -> sky, ground, indirect instanced draw ->
// tonemap.comp. GPU timestamps bracket "cull", "draw" and "tonemap".
#pragma once

#include "gpu_types.h"
#include "render/camera.h"
#include "render/render_targets.h"
#include "test_mesh.h"
#include "vk/memory.h"
#include "vk/pipeline.h"

#include <span>
#include <vector>

namespace meadow {

struct GpuTimer;

struct FieldRenderer {
    Pipeline cull;
    Pipeline tonemap;
    Pipeline sky;
    Pipeline ground;
    Pipeline instance;

    Buffer frameUniforms; // host-written each frame: the only per-frame upload
    Buffer instances;
    Buffer vertices;
    Buffer indices;
    Buffer drawCommand;
    Buffer visibleList;
    Buffer stats;
    Buffer statsReadback;

    uint32_t instanceCount = 0;
    uint32_t indexCount = 0;
    glm::vec4 groundCenterHalfSize{0.0f};
};

struct FieldStats {
    uint32_t visibleInstances = 0;
    uint32_t testedInstances = 0;
    uint64_t trianglesDrawn = 0; // instances + ground + sky
};

FieldRenderer createFieldRenderer(Context& context, const Mesh& mesh, std::span<const gpu::GpuInstance> instances);
void destroyFieldRenderer(Context& context, FieldRenderer& renderer);

// Writes the frame's uniform block. Call only when the previous frame's commands completed.
void updateFrameUniforms(FieldRenderer& renderer, const gpu::GpuFrame& frame);

// Records one frame into `targets`. At the end the HDR and LDR images are in GENERAL layout and
// the statistics are on their way to statsReadback. `timer` may be null.
void recordFieldFrame(Context& context, FieldRenderer& renderer, VkCommandBuffer cmd, const RenderTargets& targets,
                      GpuTimer* timer);

// The statistics of the last completed frame.
FieldStats readFieldStats(const FieldRenderer& renderer);

} // namespace meadow
