// Whether what a field needs fits in the device's memory, checked before anything is allocated
// (issue 10, item 6): a field too large for the device fails at load with a message that says how
// much it needs and how much there is, instead of an allocation failure halfway through creating
// the renderer or a lost device later.
//
// The figure compared is the heap the allocator (vk/memory.h) takes MemoryUse::Device memory from:
// the heap of the first DEVICE_LOCAL memory type. Of that heap meadow counts on
//   - what VK_EXT_memory_budget says this process may still allocate (heapBudget - heapUsage)
//     when the device supports the extension: it accounts for other processes and the driver;
//   - otherwise kUsableHeapFraction of the heap's size, less what meadow's allocator already holds.
// On lavapipe the heap is the machine's memory, so the check also stops a field that would drive
// a CPU-only machine into swapping or the out-of-memory killer.
// MEADOW_GPU_MEMORY_MIB=N caps what meadow counts on at N MiB: to share a GPU with other work, and
// for tests of the check on any machine.
#pragma once

#include <cstdint>
#include <string>
#include <vulkan/vulkan.h>

namespace meadow {

struct Context;

inline constexpr double kUsableHeapFraction = 0.9; // without a budget: leave a tenth to the driver and others

struct DeviceMemoryFigures {
    std::string deviceName;
    uint32_t heapIndex = 0;
    uint64_t heapBytes = 0;      // the size of the heap
    uint64_t availableBytes = 0; // what meadow may still allocate from it
    bool fromBudget = false;     // availableBytes came from VK_EXT_memory_budget
    uint64_t limitBytes = 0;     // MEADOW_GPU_MEMORY_MIB, 0 if unset; availableBytes is at most this
};

// The figures of the heap device-local buffers come from. `bytesInUse` is what meadow's allocator
// already holds there (used only without a budget, which counts it already). Throws meadow::Error
// when MEADOW_GPU_MEMORY_MIB is set but not a positive whole number.
DeviceMemoryFigures deviceMemoryFigures(VkPhysicalDevice physicalDevice, uint64_t bytesInUse);
DeviceMemoryFigures deviceMemoryFigures(const Context& context);

// Throws meadow::Error "WHAT needs X MiB of GPU memory; the device has Y MiB (...)" when
// `neededBytes` exceeds figures.availableBytes. `what` names the thing: "the field".
void checkMemoryFits(uint64_t neededBytes, const DeviceMemoryFigures& figures, const std::string& what);

// Both: the check against the context's device, as it is now.
void checkFieldMemory(const Context& context, uint64_t neededBytes, const std::string& what = "the field");

// Bytes as the messages write them: MiB with one decimal ("1536.0 MiB").
std::string formatMiB(uint64_t bytes);

} // namespace meadow
