#include "render/window.h"

#include "vk/barriers.h"
#include "vk/context.h"
#include "vk/memory.h"
#include "vk/vk_check.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace meadow {
namespace {

std::string glfwErrorText() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "unknown GLFW error";
}

void destroySwapchainResources(Context& ctx, Window& w) {
    for (VkSemaphore s : w.presentReady)
        vkDestroySemaphore(ctx.device, s, nullptr);
    w.presentReady.clear();
    w.images.clear();
    if (w.composite.image)
        destroyImage(ctx, w.composite);
    w.compositeHasFrame = false;
}

void requireCompositeFormat(Context& ctx) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice, kCompositeFormat, &props);
    const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT |
                                        VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT | VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                                        VK_FORMAT_FEATURE_TRANSFER_SRC_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
    if ((props.optimalTilingFeatures & needed) != needed)
        throw Error("the Vulkan device " + ctx.deviceName() +
                    " cannot blend into, copy and blit R8G8B8A8_UNORM images as the window needs");
}

} // namespace

void initWindowSystem() {
    if (!glfwInit())
        throw Error("cannot open a window: " + glfwErrorText() +
                    " (is there a display? set DISPLAY, or use meadow render for offscreen frames)");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw Error("cannot open a window: GLFW finds no Vulkan loader with surface support");
    }
}

void terminateWindowSystem() {
    glfwTerminate();
}

std::vector<std::string> windowInstanceExtensions() {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names)
        throw Error("cannot open a window: Vulkan has no surface extensions for this display (" + glfwErrorText() +
                    ")");
    return std::vector<std::string>(names, names + count);
}

bool windowPresentSupport(VkInstance instance, VkPhysicalDevice device, uint32_t family) {
    return glfwGetPhysicalDevicePresentationSupport(instance, device, family) == GLFW_TRUE;
}

Window createWindow(Context& ctx, const std::string& title, uint32_t width, uint32_t height) {
    Window w;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    w.window = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (!w.window)
        throw Error("cannot create a window: " + glfwErrorText());
    VK_CHECK(glfwCreateWindowSurface(ctx.instance, w.window, nullptr, &w.surface));
    VkBool32 supported = VK_FALSE;
    VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice, ctx.queueFamily, w.surface, &supported));
    if (!supported)
        throw Error("the Vulkan device " + ctx.deviceName() + " cannot present to this window");

    VkSemaphoreCreateInfo semInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VK_CHECK(vkCreateSemaphore(ctx.device, &semInfo, nullptr, &w.acquired));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fenceInfo.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VK_CHECK(vkCreateFence(ctx.device, &fenceInfo, nullptr, &w.frameFence));
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = ctx.commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(ctx.device, &alloc, &w.cmd));
    return w;
}

void destroyWindow(Context& ctx, Window& w) {
    vkDeviceWaitIdle(ctx.device);
    destroySwapchainResources(ctx, w);
    if (w.swapchain)
        vkDestroySwapchainKHR(ctx.device, w.swapchain, nullptr);
    if (w.cmd)
        vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &w.cmd);
    if (w.frameFence)
        vkDestroyFence(ctx.device, w.frameFence, nullptr);
    if (w.acquired)
        vkDestroySemaphore(ctx.device, w.acquired, nullptr);
    if (w.surface)
        vkDestroySurfaceKHR(ctx.instance, w.surface, nullptr);
    if (w.window)
        glfwDestroyWindow(w.window);
    w = Window{};
}

VkExtent2D framebufferExtent(const Window& w) {
    int width = 0, height = 0;
    glfwGetFramebufferSize(w.window, &width, &height);
    return {uint32_t(std::max(width, 0)), uint32_t(std::max(height, 0))};
}

bool recreateSwapchain(Context& ctx, Window& w) {
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx.physicalDevice, w.surface, &caps));
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == 0xFFFFFFFFu) {
        VkExtent2D fb = framebufferExtent(w);
        extent.width = std::clamp(fb.width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(fb.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    if (extent.width == 0 || extent.height == 0)
        return false; // minimised

    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        throw Error("the window's swapchain images cannot be blit targets on " + ctx.deviceName());

    uint32_t formatCount = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice, w.surface, &formatCount, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(formatCount);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice, w.surface, &formatCount, formats.data()));
    // The tonemapped image is already sRGB-encoded, so a UNORM swapchain shows it unchanged.
    VkSurfaceFormatKHR chosen{VK_FORMAT_UNDEFINED, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR};
    for (const VkSurfaceFormatKHR& f : formats)
        if ((f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) &&
            f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
            chosen = f;
            break;
        }
    if (chosen.format == VK_FORMAT_UNDEFINED)
        throw Error("the window offers no 8-bit UNORM swapchain format on " + ctx.deviceName());

    uint32_t modeCount = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(ctx.physicalDevice, w.surface, &modeCount, nullptr));
    std::vector<VkPresentModeKHR> modes(modeCount);
    VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(ctx.physicalDevice, w.surface, &modeCount, modes.data()));
    VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR; // always supported
    if (!w.vsync) {
        // Without vsync: tearing allowed (IMMEDIATE) first, else the newest frame wins (MAILBOX).
        auto has = [&](VkPresentModeKHR m) { return std::find(modes.begin(), modes.end(), m) != modes.end(); };
        if (has(VK_PRESENT_MODE_IMMEDIATE_KHR))
            mode = VK_PRESENT_MODE_IMMEDIATE_KHR;
        else if (has(VK_PRESENT_MODE_MAILBOX_KHR))
            mode = VK_PRESENT_MODE_MAILBOX_KHR;
    }

    uint32_t imageCount = std::max(caps.minImageCount + 1, 2u);
    if (caps.maxImageCount > 0)
        imageCount = std::min(imageCount, caps.maxImageCount);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = w.surface;
    info.minImageCount = imageCount;
    info.imageFormat = chosen.format;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha =
        (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
            : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    info.presentMode = mode;
    info.clipped = VK_TRUE;
    info.oldSwapchain = w.swapchain;

    // Nothing may still use the old swapchain's images or semaphores.
    VK_CHECK(vkDeviceWaitIdle(ctx.device));
    VkSwapchainKHR swapchain;
    VK_CHECK(vkCreateSwapchainKHR(ctx.device, &info, nullptr, &swapchain));
    destroySwapchainResources(ctx, w);
    if (w.swapchain)
        vkDestroySwapchainKHR(ctx.device, w.swapchain, nullptr);
    w.swapchain = swapchain;
    w.format = chosen.format;
    w.extent = extent;
    w.presentMode = mode;
    requireCompositeFormat(ctx);
    w.composite = createImage2D(ctx, extent, kCompositeFormat,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_DST_BIT);

    uint32_t count = 0;
    VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, w.swapchain, &count, nullptr));
    w.images.resize(count);
    VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, w.swapchain, &count, w.images.data()));
    VkSemaphoreCreateInfo semInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    w.presentReady.resize(count);
    for (VkSemaphore& s : w.presentReady)
        VK_CHECK(vkCreateSemaphore(ctx.device, &semInfo, nullptr, &s));
    ++w.swapchainGeneration;
    w.recreateNeeded = false;
    return true;
}

bool acquireImage(Context& ctx, Window& w, uint32_t& imageIndex) {
    VkResult r = vkAcquireNextImageKHR(ctx.device, w.swapchain, UINT64_MAX, w.acquired, VK_NULL_HANDLE, &imageIndex);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        recreateSwapchain(ctx, w);
        return false;
    }
    if (r != VK_SUBOPTIMAL_KHR)
        VK_CHECK(r);
    return true;
}

void recordFrameToComposite(VkCommandBuffer cmd, Window& w, const RenderTargets& t) {
    imageBarrier(cmd, t.ldr.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kComputeWrite, VK_IMAGE_LAYOUT_GENERAL,
                 access::kTransferRead, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    // The previous frame's blit (and a screenshot) read the composite; its contents are replaced.
    imageBarrier(cmd, w.composite.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kTransferRead, VK_IMAGE_LAYOUT_UNDEFINED,
                 access::kTransferWrite, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    if (t.extent.width == w.extent.width && t.extent.height == w.extent.height) {
        VkImageCopy copy{};
        copy.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.extent = {w.extent.width, w.extent.height, 1};
        vkCmdCopyImage(cmd, t.ldr.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, w.composite.image,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    } else {
        VkImageBlit blit{};
        blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.srcOffsets[1] = {int32_t(t.extent.width), int32_t(t.extent.height), 1};
        blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.dstOffsets[1] = {int32_t(w.extent.width), int32_t(w.extent.height), 1};
        vkCmdBlitImage(cmd, t.ldr.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, w.composite.image,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    }
    imageBarrier(cmd, w.composite.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kTransferWrite,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, access::kColorAttachmentWrite,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    // Back to GENERAL so the next frame's tonemap finds it where it expects.
    imageBarrier(cmd, t.ldr.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kTransferRead,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, access::kComputeReadWrite, VK_IMAGE_LAYOUT_GENERAL);
}

void recordCompositeToSwapchain(VkCommandBuffer cmd, Window& w, uint32_t imageIndex, Access writtenBy) {
    VkImage target = w.images[imageIndex];
    imageBarrier(cmd, w.composite.image, VK_IMAGE_ASPECT_COLOR_BIT, writtenBy, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 access::kTransferRead, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    // The acquire semaphore's wait covers the transfer stage; the layout change waits on it.
    imageBarrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_NONE},
                 VK_IMAGE_LAYOUT_UNDEFINED, access::kTransferWrite, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    // Same size; a blit because the swapchain's format may be BGRA.
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(w.composite.extent.width), int32_t(w.composite.extent.height), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[1] = {int32_t(w.extent.width), int32_t(w.extent.height), 1};
    vkCmdBlitImage(cmd, w.composite.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
    imageBarrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, access::kTransferWrite, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 access::kNone, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    w.compositeHasFrame = true;
}

std::vector<uint8_t> readCompositePixels(Context& ctx, const Window& w) {
    if (!w.compositeHasFrame)
        throw Error("the window has not shown a frame since it was last resized; no screenshot");
    const VkExtent2D e = w.composite.extent;
    const VkDeviceSize size = VkDeviceSize(e.width) * e.height * 4;
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
        // The frame's blit read it in this layout; another read needs only the execution order.
        barrier(cmd, access::kTransferRead, access::kTransferRead);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {e.width, e.height, 1};
        vkCmdCopyImageToBuffer(cmd, w.composite.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1,
                               &region);
        barrier(cmd, access::kTransferWrite, access::kHostRead);
    });
    std::vector<uint8_t> pixels(size);
    std::memcpy(pixels.data(), staging.mapped(), size);
    destroyBuffer(ctx, staging);
    return pixels;
}

void setFullscreen(Window& w, bool fullscreen) {
    if (fullscreen == w.fullscreen)
        return;
    if (fullscreen) {
        GLFWmonitor* monitor = glfwGetPrimaryMonitor();
        const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr;
        if (!mode) {
            std::fprintf(stderr, "meadow: no monitor to go fullscreen on (%s)\n", glfwErrorText().c_str());
            return;
        }
        glfwGetWindowPos(w.window, &w.windowedX, &w.windowedY);
        glfwGetWindowSize(w.window, &w.windowedWidth, &w.windowedHeight);
        glfwSetWindowMonitor(w.window, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
    } else {
        glfwSetWindowMonitor(w.window, nullptr, w.windowedX, w.windowedY, w.windowedWidth, w.windowedHeight,
                             GLFW_DONT_CARE);
    }
    w.fullscreen = fullscreen;
}

void setVsync(Context& ctx, Window& w, bool vsync) {
    w.vsync = vsync;
    // While minimised there is no swapchain to make: the first frame after restoring makes it.
    w.recreateNeeded = !recreateSwapchain(ctx, w);
}

const char* presentModeName(VkPresentModeKHR mode) {
    switch (mode) {
    case VK_PRESENT_MODE_IMMEDIATE_KHR: return "IMMEDIATE";
    case VK_PRESENT_MODE_MAILBOX_KHR: return "MAILBOX";
    case VK_PRESENT_MODE_FIFO_KHR: return "FIFO";
    case VK_PRESENT_MODE_FIFO_RELAXED_KHR: return "FIFO_RELAXED";
    default: return "other";
    }
}

bool submitAndPresent(Context& ctx, Window& w, uint32_t imageIndex) {
    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = w.acquired;
    wait.stageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal.semaphore = w.presentReady[imageIndex];
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = w.cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.waitSemaphoreInfoCount = 1;
    submit.pWaitSemaphoreInfos = &wait;
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    submit.signalSemaphoreInfoCount = 1;
    submit.pSignalSemaphoreInfos = &signal;
    VK_CHECK(vkQueueSubmit2(ctx.queue, 1, &submit, w.frameFence));

    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &w.presentReady[imageIndex];
    present.swapchainCount = 1;
    present.pSwapchains = &w.swapchain;
    present.pImageIndices = &imageIndex;
    VkResult r = vkQueuePresentKHR(ctx.queue, &present);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
        recreateSwapchain(ctx, w);
        return false;
    }
    VK_CHECK(r);
    return true;
}

} // namespace meadow
