// GPU timestamp queries: each pass is bracketed by a timestamp; the durations are read back
// after the frame's fence. Times are in milliseconds, using the device's timestampPeriod.
#pragma once

#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace meadow {

struct Context;

struct GpuTimer {
    VkQueryPool pool = VK_NULL_HANDLE;
    uint32_t capacity = 0;
    uint32_t used = 0;
    double nanosecondsPerTick = 1.0;
    uint64_t validMask = ~0ull;
    std::vector<std::string> labels; // labels[i] names the interval ending at query i + 1
};

GpuTimer createGpuTimer(Context& context, uint32_t maxTimestamps);
void destroyGpuTimer(Context& context, GpuTimer& timer);

// Starts a frame's list of timestamps (resets the pool from the host, so call it before
// recording) and writes the first one.
void beginTimestamps(Context& context, GpuTimer& timer, VkCommandBuffer cmd);
// Marks the end of the pass `label`, which began at the previous timestamp.
void markTimestamp(GpuTimer& timer, VkCommandBuffer cmd, const std::string& label);

struct PassTime {
    std::string label;
    double milliseconds;
};
// Durations of the marked passes of the last frame, after its commands completed.
std::vector<PassTime> readTimestamps(Context& context, const GpuTimer& timer);

} // namespace meadow
