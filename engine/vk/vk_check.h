// VK_CHECK and meadow's error type. VK_CHECK is always on: a failed call throws a meadow::Error
// naming the call, the VkResult and where it happened.
#pragma once

#include "core/error.h"

#include <string>
#include <vulkan/vulkan.h>

namespace meadow {

// "VK_ERROR_DEVICE_LOST" style name of a result (from the Vulkan-Hpp string tables).
std::string vkResultName(VkResult result);

[[noreturn]] void throwVkError(const char* call, VkResult result, const char* file, int line);

} // namespace meadow

#define VK_CHECK(call)                                                                                                 \
    do {                                                                                                               \
        VkResult vkCheckResult_ = (call);                                                                              \
        if (vkCheckResult_ != VK_SUCCESS)                                                                              \
            ::meadow::throwVkError(#call, vkCheckResult_, __FILE__, __LINE__);                                         \
    } while (0)
