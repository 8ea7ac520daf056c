#include "vk/context.h"

#include "vk/driver_workarounds.h"
#include "vk/memory.h"
#include "vk/vk_check.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

namespace meadow {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// Messages the validation layer sends that are known driver or layer issues, each with the
// reason it is safe to ignore. Anything else counts.
struct AllowedMessage {
    const char* idName;
    const char* reason;
};
constexpr AllowedMessage kAllowedMessages[] = {
    // The layer announces itself and its settings at the info level; that is not a finding.
    {"UNASSIGNED-khronos-validation-createinstance-status-message",
     "informational banner the layer prints when it starts"},
};

VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* counter = static_cast<ValidationCounter*>(user);
    const char* id = data->pMessageIdName ? data->pMessageIdName : "";
    for (const AllowedMessage& allowed : kAllowedMessages)
        if (std::strcmp(id, allowed.idName) == 0)
            return VK_FALSE;
    const char* label = "info";
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        label = "error";
        counter->errors++;
    } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        label = "warning";
        counter->warnings++;
    } else {
        counter->other++;
    }
    std::fprintf(stderr, "meadow: validation %s: %s\n", label, data->pMessage ? data->pMessage : id);
    return VK_FALSE;
}

bool hasLayer(const char* name) {
    uint32_t count = 0;
    VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
    std::vector<VkLayerProperties> layers(count);
    VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

int typeRank(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
    }
}

const char* typeName(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

std::string lower(std::string s) {
    for (char& c : s)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::vector<VkPhysicalDevice> enumeratePhysicalDevices(VkInstance instance) {
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    return devices;
}

// The device extensions meadow requires.
constexpr const char* kDeviceExtensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};

bool deviceHasExtension(VkPhysicalDevice pd, const char* name) {
    uint32_t extCount = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &extCount, nullptr);
    std::vector<VkExtensionProperties> exts(extCount);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &extCount, exts.data());
    return std::any_of(exts.begin(), exts.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// Everything meadow needs from a device, as a list of human-readable gaps (empty: usable).
std::vector<std::string> missingRequirements(VkPhysicalDevice pd, const ContextOptions& options, VkInstance instance,
                                             uint32_t* queueFamilyOut) {
    bool presentation = options.presentation;
    std::vector<std::string> missing;
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    if (props.apiVersion < VK_API_VERSION_1_3)
        missing.push_back("Vulkan 1.3 (device reports " + std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) + "." +
                          std::to_string(VK_API_VERSION_MINOR(props.apiVersion)) + ")");

    auto hasExt = [&](const char* name) { return deviceHasExtension(pd, name); };
    for (const char* ext : kDeviceExtensions)
        if (!hasExt(ext))
            missing.push_back(std::string("extension ") + ext);
    if (presentation && !hasExt(VK_KHR_SWAPCHAIN_EXTENSION_NAME))
        missing.push_back("extension " VK_KHR_SWAPCHAIN_EXTENSION_NAME);

    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f12};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11};
    if (props.apiVersion >= VK_API_VERSION_1_3) {
        vkGetPhysicalDeviceFeatures2(pd, &f2);
        if (!f13.dynamicRendering)
            missing.push_back("feature dynamicRendering");
        if (!f13.synchronization2)
            missing.push_back("feature synchronization2");
        if (!f13.maintenance4)
            missing.push_back("feature maintenance4");
        if (!f12.hostQueryReset)
            missing.push_back("feature hostQueryReset");
        if (!f11.shaderDrawParameters)
            missing.push_back("feature shaderDrawParameters");
        if (!f2.features.multiDrawIndirect)
            missing.push_back("feature multiDrawIndirect");
        if (!f2.features.drawIndirectFirstInstance)
            missing.push_back("feature drawIndirectFirstInstance");
        // The far field's visibility buffer: 64-bit atomicMin (far_splat.h).
        if (!f2.features.shaderInt64)
            missing.push_back("feature shaderInt64");
        if (!f12.shaderBufferInt64Atomics)
            missing.push_back("feature shaderBufferInt64Atomics");
        // The near raster's SIMD rows take their draws from a counter (near_raster.h).
        VkPhysicalDeviceVulkan11Properties p11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES};
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p11};
        vkGetPhysicalDeviceProperties2(pd, &p2);
        const VkSubgroupFeatureFlags ops = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT;
        if ((p11.subgroupSupportedStages & VK_SHADER_STAGE_COMPUTE_BIT) == 0 ||
            (p11.subgroupSupportedOperations & ops) != ops)
            missing.push_back("basic and ballot subgroup operations in compute shaders");
    }
    if (!props.limits.timestampComputeAndGraphics)
        missing.push_back("limit timestampComputeAndGraphics");

    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &familyCount, families.data());
    bool found = false;
    for (uint32_t i = 0; i < familyCount && !found; ++i) {
        VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) != need || families[i].timestampValidBits == 0)
            continue;
        if (presentation && options.presentSupport && !options.presentSupport(instance, pd, i))
            continue;
        *queueFamilyOut = i;
        found = true;
    }
    if (!found)
        missing.push_back(presentation ? "a queue family with graphics, compute, timestamps and presentation"
                                       : "a queue family with graphics, compute and timestamps");
    return missing;
}

} // namespace

bool robustAccessRequestedByEnvironment() {
    const char* v = std::getenv("MEADOW_ROBUST_BUFFER_ACCESS");
    return v && *v && std::strcmp(v, "0") != 0;
}

bool validationRequestedByEnvironment() {
    const char* v = std::getenv("MEADOW_VALIDATION");
    return v && *v && std::strcmp(v, "0") != 0;
}

std::string Context::driverDescription() const {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
    vkGetPhysicalDeviceProperties2(physicalDevice, &props2);
    return std::string(driver.driverName) + " " + driver.driverInfo;
}

std::vector<std::string> listDevices(const Context& context) {
    std::vector<std::string> lines;
    std::vector<VkPhysicalDevice> devices = enumeratePhysicalDevices(context.instance);
    for (size_t i = 0; i < devices.size(); ++i) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        lines.push_back(std::to_string(i) + ": " + props.deviceName + " [" + typeName(props.deviceType) + "]");
    }
    return lines;
}

void createContext(Context& ctx, const ContextOptions& options) {
    ctx.validationEnabled = options.validation;
    ctx.validation = std::make_unique<ValidationCounter>();
    // Before any Vulkan call: lavapipe reads its settings and picks its shader cache when it loads.
    std::string workaround = applyLavapipeWorkarounds();
    if (options.verbose && !workaround.empty())
        std::fprintf(stderr, "meadow: %s\n", workaround.c_str());

    VkResult loaderVersion = VK_SUCCESS;
    uint32_t apiVersion = 0;
    loaderVersion = vkEnumerateInstanceVersion(&apiVersion);
    if (loaderVersion != VK_SUCCESS || apiVersion < VK_API_VERSION_1_3)
        throw Error("the Vulkan loader supports only Vulkan " + std::to_string(VK_API_VERSION_MAJOR(apiVersion)) + "." +
                    std::to_string(VK_API_VERSION_MINOR(apiVersion)) + "; meadow needs 1.3");

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    for (const std::string& e : options.instanceExtensions)
        extensions.push_back(e.c_str());
    if (options.validation) {
        if (!hasLayer(kValidationLayer))
            throw Error(std::string("validation was requested but the layer ") + kValidationLayer +
                        " is not installed (Debian package vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "meadow";
    app.pEngineName = "meadow";
    app.apiVersion = VK_API_VERSION_1_3;

    // Synchronization validation is part of every validated run: hazards are bugs too.
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = debugCallback;
    messengerInfo.pUserData = ctx.validation.get();
    if (options.validation) {
        features.pNext = &messengerInfo; // also reports problems in vkCreateInstance itself
    }

    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pNext = options.validation ? &features : nullptr;
    instanceInfo.pApplicationInfo = &app;
    instanceInfo.enabledLayerCount = static_cast<uint32_t>(layers.size());
    instanceInfo.ppEnabledLayerNames = layers.data();
    instanceInfo.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    instanceInfo.ppEnabledExtensionNames = extensions.data();
    VkResult r = vkCreateInstance(&instanceInfo, nullptr, &ctx.instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw Error("no Vulkan driver found (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER); install "
                    "mesa-vulkan-drivers for lavapipe, or check VK_ICD_FILENAMES / VK_DRIVER_FILES");
    if (r == VK_ERROR_EXTENSION_NOT_PRESENT)
        throw Error("the Vulkan instance lacks an extension meadow needs (surface support for a window, or "
                    "debug utils for validation)");
    VK_CHECK(r);

    if (options.validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx.instance, "vkCreateDebugUtilsMessengerEXT"));
        VK_CHECK(create(ctx.instance, &messengerInfo, nullptr, &ctx.messenger));
    }

    std::vector<VkPhysicalDevice> devices = enumeratePhysicalDevices(ctx.instance);
    if (devices.empty())
        throw Error("no Vulkan device found: the loader found a driver but it exposes no device; install "
                    "mesa-vulkan-drivers for lavapipe, or check VK_ICD_FILENAMES / VK_DRIVER_FILES");

    std::string override = options.deviceOverride;
    if (override.empty())
        if (const char* env = std::getenv("MEADOW_DEVICE"))
            override = env;

    // Candidates in preference order; with an override, only the devices it names.
    std::vector<size_t> order(devices.size());
    for (size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    std::vector<VkPhysicalDeviceProperties> props(devices.size());
    for (size_t i = 0; i < devices.size(); ++i)
        vkGetPhysicalDeviceProperties(devices[i], &props[i]);
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return typeRank(props[a].deviceType) < typeRank(props[b].deviceType); });
    if (!override.empty()) {
        std::vector<size_t> named;
        bool numeric = override.find_first_not_of("0123456789") == std::string::npos;
        for (size_t i = 0; i < devices.size(); ++i) {
            if (numeric ? std::to_string(i) == override
                        : lower(props[i].deviceName).find(lower(override)) != std::string::npos)
                named.push_back(i);
        }
        if (named.empty()) {
            std::string list;
            for (const std::string& line : listDevices(ctx))
                list += "\n  " + line;
            throw Error("no Vulkan device matches '" + override +
                        "' (from --device or MEADOW_DEVICE); devices:" + list);
        }
        order = named;
    }

    std::string rejected;
    int chosen = -1;
    for (size_t i : order) {
        uint32_t family = 0;
        std::vector<std::string> missing = missingRequirements(devices[i], options, ctx.instance, &family);
        if (missing.empty()) {
            chosen = static_cast<int>(i);
            ctx.queueFamily = family;
            break;
        }
        rejected += std::string("\n  ") + props[i].deviceName + " lacks:";
        for (const std::string& m : missing)
            rejected += " " + m + ";";
    }
    if (chosen < 0)
        throw Error("no usable Vulkan device:" + rejected);

    ctx.physicalDevice = devices[static_cast<size_t>(chosen)];
    ctx.properties = props[static_cast<size_t>(chosen)];
    {
        VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        VkPhysicalDeviceVulkan11Properties p11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES, &driver};
        VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p11};
        vkGetPhysicalDeviceProperties2(ctx.physicalDevice, &props2);
        ctx.subgroupSize = p11.subgroupSize; // the same structure missingRequirements checks
        if (driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE) {
            std::string unsupported = lavapipeUnsupportedReason(lavapipeSettingsFromEnvironment());
            if (!unsupported.empty())
                throw Error(unsupported);
        }
    }
    vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice, &ctx.memoryProperties);
    {
        uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice, &familyCount, families.data());
        ctx.timestampValidBits = families[ctx.queueFamily].timestampValidBits;
    }
    if (options.verbose)
        std::fprintf(stderr, "meadow: device %s (%s)\n", ctx.properties.deviceName, ctx.driverDescription().c_str());

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = ctx.queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.dynamicRendering = VK_TRUE;
    f13.synchronization2 = VK_TRUE;
    f13.maintenance4 = VK_TRUE;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    f12.hostQueryReset = VK_TRUE;
    f12.shaderBufferInt64Atomics = VK_TRUE;
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f12};
    f11.shaderDrawParameters = VK_TRUE;
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11};
    f2.features.multiDrawIndirect = VK_TRUE;
    f2.features.drawIndirectFirstInstance = VK_TRUE;
    f2.features.shaderInt64 = VK_TRUE;

    std::vector<const char*> deviceExtensions(std::begin(kDeviceExtensions), std::end(kDeviceExtensions));
    if (options.presentation)
        deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);

    // MEADOW_ROBUST_BUFFER_ACCESS=1: every buffer access bounds-checked by the driver (out of range
    // reads give zero, writes are dropped), robustness2's tighter rules where the device has them.
    // A frame that changes under it read or wrote outside a buffer (docs/ROBUSTNESS.md).
    VkPhysicalDeviceRobustness2FeaturesEXT robustness2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
    if (robustAccessRequestedByEnvironment()) {
        VkPhysicalDeviceFeatures supported;
        vkGetPhysicalDeviceFeatures(ctx.physicalDevice, &supported);
        if (!supported.robustBufferAccess)
            throw Error(std::string("MEADOW_ROBUST_BUFFER_ACCESS: ") + ctx.properties.deviceName +
                        " lacks the feature robustBufferAccess");
        f2.features.robustBufferAccess = VK_TRUE;
        VkPhysicalDeviceRobustness2FeaturesEXT has{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
        VkPhysicalDeviceFeatures2 query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &has};
        if (deviceHasExtension(ctx.physicalDevice, VK_EXT_ROBUSTNESS_2_EXTENSION_NAME)) {
            vkGetPhysicalDeviceFeatures2(ctx.physicalDevice, &query);
            robustness2.robustBufferAccess2 = has.robustBufferAccess2;
            robustness2.robustImageAccess2 = has.robustImageAccess2;
            robustness2.pNext = f2.pNext;
            f2.pNext = &robustness2;
            deviceExtensions.push_back(VK_EXT_ROBUSTNESS_2_EXTENSION_NAME);
        }
        if (options.verbose)
            std::fprintf(stderr, "meadow: robust buffer access on (robustBufferAccess2 %s)\n",
                         robustness2.robustBufferAccess2 ? "on" : "not available");
    }

    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &f2};
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.enabledExtensionCount = static_cast<uint32_t>(deviceExtensions.size());
    deviceInfo.ppEnabledExtensionNames = deviceExtensions.data();
    VK_CHECK(vkCreateDevice(ctx.physicalDevice, &deviceInfo, nullptr, &ctx.device));
    vkGetDeviceQueue(ctx.device, ctx.queueFamily, 0, &ctx.queue);

    ctx.cmdPushDescriptorSet =
        reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(ctx.device, "vkCmdPushDescriptorSetKHR"));
    if (!ctx.cmdPushDescriptorSet)
        throw Error("vkCmdPushDescriptorSetKHR is missing although the device lists VK_KHR_push_descriptor");

    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = ctx.queueFamily;
    VK_CHECK(vkCreateCommandPool(ctx.device, &poolInfo, nullptr, &ctx.commandPool));

    ctx.memory = std::make_unique<MemoryAllocator>(ctx);
}

Context::~Context() {
    destroyContext(*this);
}

void destroyContext(Context& ctx) {
    if (ctx.device) {
        vkDeviceWaitIdle(ctx.device);
        ctx.memory.reset();
        vkDestroyCommandPool(ctx.device, ctx.commandPool, nullptr);
        vkDestroyDevice(ctx.device, nullptr);
    }
    if (ctx.messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx.instance, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(ctx.instance, ctx.messenger, nullptr);
    }
    if (ctx.instance)
        vkDestroyInstance(ctx.instance, nullptr);
    ctx.device = VK_NULL_HANDLE;
    ctx.messenger = VK_NULL_HANDLE;
    ctx.instance = VK_NULL_HANDLE;
}

VkCommandBuffer beginOneShot(Context& ctx) {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = ctx.commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd;
    VK_CHECK(vkAllocateCommandBuffers(ctx.device, &alloc, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    return cmd;
}

void endOneShotAndWait(Context& ctx, VkCommandBuffer cmd) {
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    VK_CHECK(vkCreateFence(ctx.device, &fenceInfo, nullptr, &fence));
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    VK_CHECK(vkQueueSubmit2(ctx.queue, 1, &submit, fence));
    VK_CHECK(vkWaitForFences(ctx.device, 1, &fence, VK_TRUE, UINT64_MAX));
    vkDestroyFence(ctx.device, fence, nullptr);
    vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &cmd);
}

} // namespace meadow
