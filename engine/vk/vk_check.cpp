#include "vk/vk_check.h"

#include <cctype>
#include <vulkan/vulkan.hpp>
#include <vulkan/vulkan_to_string.hpp>

namespace meadow {

std::string vkResultName(VkResult result) {
    // Vulkan-Hpp names results "ErrorDeviceLost"; turn that back into the C spelling people
    // search for.
    std::string camel = vk::to_string(static_cast<vk::Result>(result));
    if (camel.rfind("invalid", 0) == 0)
        return "VkResult(" + std::to_string(static_cast<int>(result)) + ")";
    std::string out = "VK_";
    for (size_t i = 0; i < camel.size(); ++i) {
        char c = camel[i];
        bool upper = c >= 'A' && c <= 'Z';
        if (upper && i > 0) {
            // Keep vendor suffixes together: "KHR", "EXT".
            bool prevUpper = camel[i - 1] >= 'A' && camel[i - 1] <= 'Z';
            if (!prevUpper)
                out += '_';
        }
        out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    return out;
}

void throwVkError(const char* call, VkResult result, const char* file, int line) {
    throw Error(std::string("Vulkan call failed: ") + call + " returned " + vkResultName(result) + " (" + file + ":" +
                std::to_string(line) + ")");
}

} // namespace meadow
