// The window target: a GLFW window with a Vulkan swapchain that survives resize and minimise.
// Frames are rendered into RenderTargets and the tonemapped image is blitted to the swapchain
// image, so the window shows exactly what offscreen rendering writes to PNG.
#pragma once

#include "render/render_targets.h"

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
};

Window createWindow(Context& context, const std::string& title, uint32_t width, uint32_t height);
void destroyWindow(Context& context, Window& window);

// Current framebuffer size; zero while minimised.
VkExtent2D framebufferExtent(const Window& window);

// (Re)creates the swapchain for the current framebuffer size. Returns false while minimised.
bool recreateSwapchain(Context& context, Window& window);

// Acquires the next image; returns false if the swapchain had to be recreated (skip the frame).
bool acquireImage(Context& context, Window& window, uint32_t& imageIndex);

// Records the blit of `targets.ldr` (GENERAL, written by the tonemap pass) to swapchain image
// `imageIndex`, scaled to fit, and its transition for presentation.
void recordBlitToSwapchain(VkCommandBuffer cmd, const Window& window, uint32_t imageIndex,
                           const RenderTargets& targets);

// Submits the window's command buffer (waiting on the acquire) and presents. Returns false when
// the swapchain is out of date and was recreated.
bool submitAndPresent(Context& context, Window& window, uint32_t imageIndex);

} // namespace meadow
