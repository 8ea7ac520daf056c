// The Vulkan context: instance, the chosen physical device, one logical device with a single
// graphics+compute queue, the validation messenger and the memory sub-allocator.
//
// Device choice: a discrete GPU when present, then integrated, virtual, and last a CPU
// implementation (lavapipe). `deviceOverride` (flag --device, environment MEADOW_DEVICE) picks by
// index into the enumeration order or by a case-insensitive part of the device name.
// Every feature meadow needs is checked before the device is created; a missing one is reported
// by name.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace meadow {

class MemoryAllocator;

struct ContextOptions {
    bool validation = false;                     // VK_LAYER_KHRONOS_validation with synchronization validation
    std::string deviceOverride;                  // empty: automatic choice
    std::vector<std::string> instanceExtensions; // e.g. what GLFW needs for a surface
    bool presentation = false;                   // the queue must be able to present (window target)
    // Whether queue family `family` of a device can present (the window target answers this
    // through GLFW, so the core needs no windowing library).
    std::function<bool(VkInstance, VkPhysicalDevice, uint32_t family)> presentSupport;
    bool verbose = false; // print which device was chosen
};

// Counts the messages the validation layer sends. Each message is printed to stderr as it comes.
struct ValidationCounter {
    std::atomic<uint32_t> errors{0};
    std::atomic<uint32_t> warnings{0};
    std::atomic<uint32_t> other{0};
    uint32_t total() const { return errors + warnings + other; }
};

struct Context {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool commandPool = VK_NULL_HANDLE; // for one-shot and per-frame command buffers

    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memoryProperties{};
    uint32_t timestampValidBits = 0;
    uint32_t subgroupSize = 0; // VkPhysicalDeviceVulkan11Properties: lavapipe's SIMD width in lanes
    bool validationEnabled = false;
    std::unique_ptr<ValidationCounter> validation;
    std::unique_ptr<MemoryAllocator> memory;
    // Every byte the CPU has written for the device: mapped buffers (vk/memory.h writeMapped,
    // hostWriteAt), uploads through staging, push constants (vk/pipeline.h pushConstants). The
    // per-frame upload figures are differences of it.
    uint64_t hostBytesWritten = 0;

    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

    std::string deviceName() const { return properties.deviceName; }
    std::string driverDescription() const;

    Context() = default;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;
    // What destroyContext has not destroyed yet (it may be called first, and more than once): a
    // command that stops on an error leaves no device or instance behind.
    ~Context();
};

// Throws meadow::Error with a message naming what is missing (no driver, no device, a feature).
void createContext(Context& context, const ContextOptions& options);
void destroyContext(Context& context);

// A short line per physical device: "0: llvmpipe (LLVM 15.0.6, 256 bits) [cpu]".
std::vector<std::string> listDevices(const Context& context);

// True when validation was requested by the environment (MEADOW_VALIDATION=1).
bool validationRequestedByEnvironment();

// True when MEADOW_ROBUST_BUFFER_ACCESS=1: createContext turns on the device's robust buffer
// access (and robustBufferAccess2 where it has VK_EXT_robustness2), so that no access leaves its
// buffer; a frame that differs from the same frame without it read or wrote outside one.
bool robustAccessRequestedByEnvironment();

// Records into a fresh primary command buffer, submits, and waits for it to finish.
template <typename Record> void submitAndWait(Context& context, Record&& record);
VkCommandBuffer beginOneShot(Context& context);
void endOneShotAndWait(Context& context, VkCommandBuffer cmd);

template <typename Record> void submitAndWait(Context& context, Record&& record) {
    VkCommandBuffer cmd = beginOneShot(context);
    record(cmd);
    endOneShotAndWait(context, cmd);
}

} // namespace meadow
