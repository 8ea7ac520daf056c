// The walkthrough's heads-up display: Dear ImGui (Debian's libimgui-dev, with its GLFW and Vulkan
// backends) drawn over the window's composite image, so screenshots show it too.
//
// Dear ImGui 1.86's Vulkan backend predates dynamic rendering: the HUD owns a one-subpass render
// pass over the composite (LOAD, STORE, COLOR_ATTACHMENT_OPTIMAL in and out; the barriers around
// it are the window's) and a framebuffer, remade when the swapchain is.
#pragma once

#include "render/window.h"

#include <vulkan/vulkan.h>

namespace meadow {

struct Context;

struct Hud {
    VkRenderPass renderPass = VK_NULL_HANDLE;
    VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    uint32_t framebufferGeneration = ~0u; // the window's swapchainGeneration it was made for
    bool imgui = false;                   // the ImGui context and backends are up
};

// Creates the ImGui context, its GLFW backend on `window` (chained onto callbacks already
// installed, such as attachInput's) and its Vulkan backend, and uploads the font (waits).
Hud createHud(Context& context, Window& window);
void destroyHud(Context& context, Hud& hud);

// Starts an ImGui frame (after glfwPollEvents), laid out for the window's current extent;
// widgets may be issued until recordHud.
void beginHudFrame(const Window& window);
// Whether ImGui wants the mouse (hovering a panel) or the keyboard (a text field is active).
bool hudWantsMouse();
bool hudWantsKeyboard();

// Ends the ImGui frame and records its draw over the window's composite, which must be in
// COLOR_ATTACHMENT_OPTIMAL (recordFrameToComposite); it stays there, written as
// access::kColorAttachmentWrite. With `visible` false nothing is drawn (the frame still ends).
void recordHud(Context& context, Hud& hud, VkCommandBuffer cmd, Window& window, bool visible);

} // namespace meadow
