// The offscreen target: renders frames of a field into images in GPU memory, one frame in
// flight, with GPU timestamps per pass. Used by `meadow render` (frames to PNG/EXR), `meadow
// bench` and the tests.
#pragma once

#include "render/field_renderer.h"
#include "vk/timestamps.h"

namespace meadow {

struct Offscreen {
    RenderTargets targets;
    GpuTimer timer;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
};

Offscreen createOffscreen(Context& context, VkExtent2D extent, HdrContents hdr = HdrContents::Frame);
void destroyOffscreen(Context& context, Offscreen& offscreen);

struct FrameTimings {
    double cpuRecordSubmitMs = 0.0; // recording and submitting on the CPU
    double wallMs = 0.0;            // from the start of the frame until its fence signalled
    std::vector<PassTime> gpu;      // per pass
};

// Writes the frame's uniforms from `state` (updateFrame), records and submits one frame, and waits for it.
FrameTimings renderOffscreenFrame(Context& context, FieldRenderer& renderer, Offscreen& offscreen,
                                  const FrameState& state);

} // namespace meadow
