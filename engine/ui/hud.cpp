#include "ui/hud.h"

#include "vk/context.h"
#include "vk/vk_check.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

namespace meadow {
namespace {

// The backend reports its own Vulkan calls' results here.
void checkImguiVkResult(VkResult result) {
    if (result != VK_SUCCESS)
        throwVkError("a Vulkan call in Dear ImGui's Vulkan backend", result, __FILE__, __LINE__);
}

VkRenderPass createHudRenderPass(Context& ctx) {
    VkAttachmentDescription color{};
    color.format = kCompositeFormat;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD; // the frame is already there
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    // No layout changes inside: the window's barriers around the pass order everything.
    color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &color;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    VkRenderPass pass;
    VK_CHECK(vkCreateRenderPass(ctx.device, &info, nullptr, &pass));
    return pass;
}

} // namespace

Hud createHud(Context& ctx, Window& window) {
    Hud hud;
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    hud.imgui = true;
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini in the user's folder
    io.LogFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGuiStyle& style = ImGui::GetStyle();
    style.WindowRounding = 4.0f;
    style.Colors[ImGuiCol_WindowBg].w = 0.82f;

    try {
        if (!ImGui_ImplGlfw_InitForVulkan(window.window, true))
            throw Error("Dear ImGui's GLFW backend did not start");
        hud.renderPass = createHudRenderPass(ctx);
        // The backend allocates one descriptor set: the font texture.
        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
        VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        poolInfo.maxSets = 1;
        poolInfo.poolSizeCount = 1;
        poolInfo.pPoolSizes = &size;
        VK_CHECK(vkCreateDescriptorPool(ctx.device, &poolInfo, nullptr, &hud.descriptorPool));

        ImGui_ImplVulkan_InitInfo info{};
        info.Instance = ctx.instance;
        info.PhysicalDevice = ctx.physicalDevice;
        info.Device = ctx.device;
        info.QueueFamily = ctx.queueFamily;
        info.Queue = ctx.queue;
        info.DescriptorPool = hud.descriptorPool;
        info.Subpass = 0;
        // The backend keeps ImageCount sets of vertex buffers and rotates through them; with one
        // frame in flight (the window waits for each frame's fence) two suffice.
        info.MinImageCount = 2;
        info.ImageCount = 2;
        info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
        info.CheckVkResultFn = checkImguiVkResult;
        if (!ImGui_ImplVulkan_Init(&info, hud.renderPass))
            throw Error("Dear ImGui's Vulkan backend did not start");
        submitAndWait(ctx, [&](VkCommandBuffer cmd) {
            if (!ImGui_ImplVulkan_CreateFontsTexture(cmd))
                throw Error("Dear ImGui's Vulkan backend could not make its font texture");
        });
        ImGui_ImplVulkan_DestroyFontUploadObjects();
    } catch (...) {
        destroyHud(ctx, hud);
        throw;
    }
    return hud;
}

void destroyHud(Context& ctx, Hud& hud) {
    if (ctx.device)
        vkDeviceWaitIdle(ctx.device);
    if (hud.imgui) {
        ImGuiIO& io = ImGui::GetIO();
        if (io.BackendRendererUserData)
            ImGui_ImplVulkan_Shutdown();
        if (io.BackendPlatformUserData)
            ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (hud.framebuffer)
        vkDestroyFramebuffer(ctx.device, hud.framebuffer, nullptr);
    if (hud.descriptorPool)
        vkDestroyDescriptorPool(ctx.device, hud.descriptorPool, nullptr);
    if (hud.renderPass)
        vkDestroyRenderPass(ctx.device, hud.renderPass, nullptr);
    hud = Hud{};
}

void beginHudFrame(const Window& window) {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    // Lay out for the image ImGui draws into (the composite, at the swapchain's extent), which can
    // differ from GLFW's window size for a frame while a resize settles.
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(window.extent.width), float(window.extent.height));
    io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
    ImGui::NewFrame();
}

bool hudWantsMouse() {
    return ImGui::GetIO().WantCaptureMouse;
}

bool hudWantsKeyboard() {
    return ImGui::GetIO().WantCaptureKeyboard || ImGui::GetIO().WantTextInput;
}

void recordHud(Context& ctx, Hud& hud, VkCommandBuffer cmd, Window& window, bool visible) {
    ImGui::Render();
    if (!visible)
        return;
    if (hud.framebufferGeneration != window.swapchainGeneration || !hud.framebuffer) {
        if (hud.framebuffer)
            vkDestroyFramebuffer(ctx.device, hud.framebuffer, nullptr); // its frame completed (fence)
        VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        info.renderPass = hud.renderPass;
        info.attachmentCount = 1;
        info.pAttachments = &window.composite.view;
        info.width = window.composite.extent.width;
        info.height = window.composite.extent.height;
        info.layers = 1;
        VK_CHECK(vkCreateFramebuffer(ctx.device, &info, nullptr, &hud.framebuffer));
        hud.framebufferGeneration = window.swapchainGeneration;
    }
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = hud.renderPass;
    begin.framebuffer = hud.framebuffer;
    begin.renderArea = {{0, 0}, window.composite.extent};
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
}

} // namespace meadow
