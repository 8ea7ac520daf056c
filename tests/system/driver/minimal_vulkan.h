// The few lines of plain Vulkan the driver reproducers share (vs_store_check.cpp,
// cs_caps_check.cpp): they use nothing of meadow, so that what they show is the driver's alone.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vulkan/vulkan.h>

namespace minimal {

// The program's name in messages; set it first thing in main.
inline const char* program = "reproducer";

// Exits with status 2 (not the driver fault a reproducer shows) when a call fails.
inline void check(VkResult result, const char* what) {
    if (result != VK_SUCCESS) {
        std::fprintf(stderr, "%s: %s failed (VkResult %d)\n", program, what, int(result));
        std::exit(2);
    }
}

inline uint32_t memoryType(VkPhysicalDevice gpu, uint32_t bits, VkMemoryPropertyFlags flags) {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(gpu, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags)
            return i;
    std::fprintf(stderr, "%s: no suitable memory type\n", program);
    std::exit(2);
}

// The first device's queue family 0, with `features` (a pNext chain, may be null) enabled.
struct Device {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice gpu = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties props{};
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
};

inline Device createDevice(const void* features) {
    Device d;
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pApplicationInfo = &app;
    check(vkCreateInstance(&instanceInfo, nullptr, &d.instance), "vkCreateInstance");
    uint32_t gpuCount = 1;
    VkResult enumerated = vkEnumeratePhysicalDevices(d.instance, &gpuCount, &d.gpu);
    if ((enumerated != VK_SUCCESS && enumerated != VK_INCOMPLETE) || gpuCount == 0) {
        std::fprintf(stderr, "%s: no Vulkan device\n", program);
        std::exit(2);
    }
    vkGetPhysicalDeviceProperties(d.gpu, &d.props);
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = 0;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, features};
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    check(vkCreateDevice(d.gpu, &deviceInfo, nullptr, &d.device), "vkCreateDevice");
    vkGetDeviceQueue(d.device, 0, 0, &d.queue);
    return d;
}

inline void destroyDevice(Device& d) {
    vkDestroyDevice(d.device, nullptr);
    vkDestroyInstance(d.instance, nullptr);
}

} // namespace minimal
