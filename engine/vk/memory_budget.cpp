#include "vk/memory_budget.h"

#include "core/error.h"
#include "vk/context.h"
#include "vk/memory.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace meadow {
namespace {

bool supportsMemoryBudget(VkPhysicalDevice physicalDevice) {
    uint32_t count = 0;
    if (vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, nullptr) != VK_SUCCESS)
        return false;
    std::vector<VkExtensionProperties> extensions(count);
    if (vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, extensions.data()) != VK_SUCCESS)
        return false;
    for (const VkExtensionProperties& e : extensions)
        if (std::strcmp(e.extensionName, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME) == 0)
            return true;
    return false;
}

} // namespace

std::string formatMiB(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / double(1ull << 20));
    return text;
}

DeviceMemoryFigures deviceMemoryFigures(VkPhysicalDevice physicalDevice, uint64_t bytesInUse) {
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(physicalDevice, &properties);
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
    const bool haveBudget = supportsMemoryBudget(physicalDevice);
    VkPhysicalDeviceMemoryProperties2 memory{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
    if (haveBudget)
        memory.pNext = &budget;
    vkGetPhysicalDeviceMemoryProperties2(physicalDevice, &memory);
    const VkPhysicalDeviceMemoryProperties& mp = memory.memoryProperties;

    DeviceMemoryFigures figures;
    figures.deviceName = properties.deviceName;
    // The allocator's choice for MemoryUse::Device: the first DEVICE_LOCAL type (vk/memory.cpp).
    figures.heapIndex = mp.memoryTypeCount > 0 ? mp.memoryTypes[0].heapIndex : 0;
    for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
        if (mp.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) {
            figures.heapIndex = mp.memoryTypes[i].heapIndex;
            break;
        }
    figures.heapBytes = mp.memoryHeapCount > figures.heapIndex ? mp.memoryHeaps[figures.heapIndex].size : 0;
    if (haveBudget && budget.heapBudget[figures.heapIndex] > 0) {
        const uint64_t allowed = budget.heapBudget[figures.heapIndex], used = budget.heapUsage[figures.heapIndex];
        figures.availableBytes = allowed > used ? allowed - used : 0;
        figures.fromBudget = true;
    } else {
        const auto usable = uint64_t(double(figures.heapBytes) * kUsableHeapFraction);
        figures.availableBytes = usable > bytesInUse ? usable - bytesInUse : 0;
    }
    if (const char* limit = std::getenv("MEADOW_GPU_MEMORY_MIB"); limit && *limit) {
        char* end = nullptr;
        const unsigned long long mib = std::strtoull(limit, &end, 10);
        if (*end != '\0' || mib == 0 || mib > (1ull << 40))
            throw Error(std::string("MEADOW_GPU_MEMORY_MIB '") + limit + "' is not a positive number of MiB");
        figures.limitBytes = uint64_t(mib) << 20;
        const uint64_t left = figures.limitBytes > bytesInUse ? figures.limitBytes - bytesInUse : 0;
        figures.availableBytes = std::min(figures.availableBytes, left);
    }
    return figures;
}

DeviceMemoryFigures deviceMemoryFigures(const Context& context) {
    return deviceMemoryFigures(context.physicalDevice, context.memory ? context.memory->bytesInUse() : 0);
}

void checkMemoryFits(uint64_t neededBytes, const DeviceMemoryFigures& figures, const std::string& what) {
    if (neededBytes <= figures.availableBytes)
        return;
    std::string detail = formatMiB(figures.availableBytes) + " of it " +
                         (figures.fromBudget ? "available to meadow now (VK_EXT_memory_budget)"
                                             : "usable (" + std::to_string(int(kUsableHeapFraction * 100.0 + 0.5)) +
                                                   "% of the heap, less what meadow holds)");
    if (figures.limitBytes != 0)
        detail += ", MEADOW_GPU_MEMORY_MIB allowing " + formatMiB(figures.limitBytes);
    throw Error(what + " needs " + formatMiB(neededBytes) + " of GPU memory; the device has " +
                formatMiB(figures.heapBytes) + " (" + figures.deviceName + ", heap " +
                std::to_string(figures.heapIndex) + ", " + detail +
                "): use fewer clumps (meadow bench --clumps), fewer tiles, or a device with more memory");
}

void checkFieldMemory(const Context& context, uint64_t neededBytes, const std::string& what) {
    checkMemoryFits(neededBytes, deviceMemoryFigures(context), what);
}

} // namespace meadow
