// The window target: a GLFW window with a Vulkan swapchain that survives resize, minimise,
// fullscreen and a change of present mode. Frames are rendered into RenderTargets; the tonemapped
// image is copied into the window's composite image (what offscreen rendering writes to PNG),
// overlays such as the HUD draw onto the composite, and the composite is blitted to the swapchain
// image. A screenshot reads the composite: exactly what the window shows.
#pragma once

#include "render/render_targets.h"
#include "vk/barriers.h"

#include <string>
#include <vector>
#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace meadow {

struct Context;

// GLFW's part of the context options: instance extensions and presentation support. Throws
// meadow::Error when there is no display or GLFW cannot use Vulkan.
void initWindowSystem();
void terminateWindowSystem();
std::vector<std::string> windowInstanceExtensions();
bool windowPresentSupport(VkInstance instance, VkPhysicalDevice device, uint32_t family);

struct Window {
    GLFWwindow* window = nullptr;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    bool vsync = true;
    std::vector<VkImage> images;
    std::vector<VkSemaphore> presentReady; // one per swapchain image: rendering done, may present
    VkSemaphore acquired = VK_NULL_HANDLE; // one frame in flight, so one suffices
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence frameFence = VK_NULL_HANDLE;
    uint32_t swapchainGeneration = 0; // bumps on each recreation
    VkPresentModeKHR presentMode = VK_PRESENT_MODE_FIFO_KHR;
    bool recreateNeeded = false; // a setting changed while the swapchain could not be remade

    // kCompositeFormat at the swapchain's extent; after a frame it is in TRANSFER_SRC_OPTIMAL.
    Image composite;
    bool compositeHasFrame = false; // false until a frame was recorded into this composite

    bool fullscreen = false;
    int windowedX = 0, windowedY = 0, windowedWidth = 0, windowedHeight = 0; // to come back to
};

inline constexpr VkFormat kCompositeFormat = VK_FORMAT_R8G8B8A8_UNORM; // as RenderTargets::ldr

Window createWindow(Context& context, const std::string& title, uint32_t width, uint32_t height);
void destroyWindow(Context& context, Window& window);

// Current framebuffer size; zero while minimised.
VkExtent2D framebufferExtent(const Window& window);

// (Re)creates the swapchain for the current framebuffer size. Returns false while minimised.
bool recreateSwapchain(Context& context, Window& window);

// Acquires the next image; returns false if the swapchain had to be recreated (skip the frame).
bool acquireImage(Context& context, Window& window, uint32_t& imageIndex);

// Records the copy of `targets.ldr` (GENERAL, written by the tonemap pass) into the composite,
// and leaves the composite in COLOR_ATTACHMENT_OPTIMAL for overlays (and ldr back in GENERAL).
void recordFrameToComposite(VkCommandBuffer cmd, Window& window, const RenderTargets& targets);

// Records the blit of the composite (COLOR_ATTACHMENT_OPTIMAL, last written as `writtenBy`) to
// swapchain image `imageIndex` and its transition for presentation; the composite ends in
// TRANSFER_SRC_OPTIMAL.
void recordCompositeToSwapchain(VkCommandBuffer cmd, Window& window, uint32_t imageIndex, Access writtenBy);

// The composite's pixels (8-bit RGBA, sRGB-encoded), after the frame's commands completed and
// before the next frame is recorded. Records and waits on its own command buffer.
std::vector<uint8_t> readCompositePixels(Context& context, const Window& window);

// Fullscreen on the primary monitor at its current mode, or back to the window as it was. The
// framebuffer changes size: the next frame recreates the swapchain.
void setFullscreen(Window& window, bool fullscreen);

// Vsync on: FIFO (always supported). Off: IMMEDIATE, else MAILBOX, else FIFO (say so). Recreates
// the swapchain (waits for the device).
void setVsync(Context& context, Window& window, bool vsync);
const char* presentModeName(VkPresentModeKHR mode);

// Submits the window's command buffer (waiting on the acquire) and presents. Returns false when
// the swapchain is out of date and was recreated.
bool submitAndPresent(Context& context, Window& window, uint32_t imageIndex);

} // namespace meadow
