// A minimal Vulkan program that draws N vertices, for each N in a range, with a vertex shader of
// many outputs (vs_outputs.vert.glsl). It uses nothing of meadow (docs/ROBUSTNESS.md, "lavapipe and
// the CPU it compiles for").
//
// lavapipe (Mesa 22.3, LLVM 15) shades vertices in its draw module: JIT code that shades
// lp_native_vector_width / 32 vertices per loop iteration, storing whole vectors of vertices, into
// a heap block of align(count, lp_native_vector_width / 32) vertices + 512 bytes. The JIT code
// goes into Mesa's on-disk shader cache, whose key holds the CPU caps (GALLIUM_OVERRIDE_CPU_CAPS)
// but not LP_NATIVE_VECTOR_WIDTH. A process at width 128 that finds the vertex shader cached by
// one at width 256 runs the 8-wide code on a block rounded to 4 vertices: the last iteration
// stores up to 4 vertices (720 bytes here) past it. glibc aborts later, or a guard allocator
// (Electric Fence) stops the store itself.
//
// So the program first fills a private, empty shader cache (a temporary MESA_SHADER_CACHE_DIR) from
// a child process at LP_NATIVE_VECTOR_WIDTH=256 (VSC_WARM_WIDTH overrides it; 0: no child, a
// cold cache), then draws at the caller's settings. Under a guard allocator it fails on a driver
// that has the fault and passes on one that does not:
//
//   LD_PRELOAD=/usr/lib/libefence.so EF_ALIGNMENT=16 LP_NATIVE_VECTOR_WIDTH=128 vs_store_check 1 64
//
//   meadow_vs_store_check [FIRST LAST]   vertex counts FIRST..LAST (default 1..96)
#include <cstdint>

#include "vs_outputs.frag.h"
#include "vs_outputs.vert.h"

#include "minimal_vulkan.h"
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

using minimal::check;

namespace {

VkShaderModule shaderModule(VkDevice device, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = bytes;
    info.pCode = code;
    VkShaderModule module;
    check(vkCreateShaderModule(device, &info, nullptr, &module), "vkCreateShaderModule");
    return module;
}

} // namespace

int main(int argc, char** argv) {
    minimal::program = "vs_store_check";
    uint32_t first = 1, last = 96;
    if (argc == 3) {
        first = uint32_t(std::strtoul(argv[1], nullptr, 10));
        last = uint32_t(std::strtoul(argv[2], nullptr, 10));
    }
    if (argc != 1 && argc != 3) {
        std::fprintf(stderr, "usage: %s [FIRST LAST]\n", argv[0]);
        return 2;
    }

    // Before the driver loads (it reads its environment once): a private shader cache, filled by a
    // child that draws once at the warm-up width.
    std::string cacheDir;
    const char* warmWidth = std::getenv("VSC_WARM_WIDTH");
    if (!warmWidth)
        warmWidth = "256";
    if (!std::getenv("VSC_WARMING") && std::strcmp(warmWidth, "0") != 0) {
        char dir[] = "/tmp/vs_store_check.XXXXXX";
        if (!mkdtemp(dir)) {
            std::perror("vs_store_check: mkdtemp");
            return 2;
        }
        cacheDir = dir;
        setenv("MESA_SHADER_CACHE_DIR", dir, 1);
        unsetenv("MESA_SHADER_CACHE_DISABLE");
        pid_t child = fork();
        if (child == 0) {
            setenv("LP_NATIVE_VECTOR_WIDTH", warmWidth, 1);
            setenv("VSC_WARMING", "1", 1);
            char* args[] = {argv[0], const_cast<char*>("3"), const_cast<char*>("3"), nullptr};
            execv("/proc/self/exe", args);
            std::_Exit(127);
        }
        int status = 0;
        if (child < 0 || waitpid(child, &status, 0) != child || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            std::fprintf(stderr, "vs_store_check: the warm-up at LP_NATIVE_VECTOR_WIDTH=%s failed\n", warmWidth);
            std::filesystem::remove_all(cacheDir);
            return 2;
        }
    }

    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.dynamicRendering = VK_TRUE;
    f13.synchronization2 = VK_TRUE;
    minimal::Device vk = minimal::createDevice(&f13);
    VkPhysicalDevice gpu = vk.gpu;
    VkDevice device = vk.device;
    VkQueue queue = vk.queue;

    // A 16 x 16 colour target.
    const VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    VkImageCreateInfo imageInfo{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    imageInfo.imageType = VK_IMAGE_TYPE_2D;
    imageInfo.format = format;
    imageInfo.extent = {16, 16, 1};
    imageInfo.mipLevels = 1;
    imageInfo.arrayLayers = 1;
    imageInfo.samples = VK_SAMPLE_COUNT_1_BIT;
    imageInfo.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    VkImage image;
    check(vkCreateImage(device, &imageInfo, nullptr, &image), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = minimal::memoryType(gpu, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkDeviceMemory memory;
    check(vkAllocateMemory(device, &alloc, nullptr, &memory), "vkAllocateMemory");
    check(vkBindImageMemory(device, image, memory, 0), "vkBindImageMemory");
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view;
    check(vkCreateImageView(device, &viewInfo, nullptr, &view), "vkCreateImageView");

    // The pipeline: no vertex input, triangles, dynamic viewport and scissor.
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    VkPipelineLayout layout;
    check(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout), "vkCreatePipelineLayout");
    VkShaderModule vert = shaderModule(device, kVert, sizeof(kVert));
    VkShaderModule frag = shaderModule(device, kFrag, sizeof(kFrag));
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag;
    stages[1].pName = "main";
    VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineColorBlendAttachmentState blendAttachment{};
    blendAttachment.colorWriteMask = 0xf;
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = 1;
    blend.pAttachments = &blendAttachment;
    VkDynamicState dynamicStates[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamicStates;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &format;
    VkGraphicsPipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    pipelineInfo.stageCount = 2;
    pipelineInfo.pStages = stages;
    pipelineInfo.pVertexInputState = &vertexInput;
    pipelineInfo.pInputAssemblyState = &assembly;
    pipelineInfo.pViewportState = &viewport;
    pipelineInfo.pRasterizationState = &raster;
    pipelineInfo.pMultisampleState = &multisample;
    pipelineInfo.pColorBlendState = &blend;
    pipelineInfo.pDynamicState = &dynamic;
    pipelineInfo.layout = layout;
    VkPipeline pipeline;
    check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &pipeline),
          "vkCreateGraphicsPipelines");

    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    VkCommandPool pool;
    check(vkCreateCommandPool(device, &poolInfo, nullptr, &pool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cmdInfo.commandPool = pool;
    cmdInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cmdInfo.commandBufferCount = 1;
    VkCommandBuffer cmd;
    check(vkAllocateCommandBuffers(device, &cmdInfo, &cmd), "vkAllocateCommandBuffers");

    // One submission per vertex count: each draw's shaded vertices are a heap block of their own.
    for (uint32_t count = first; count <= last; ++count) {
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
        VkImageMemoryBarrier2 toAttachment{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        toAttachment.srcStageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        toAttachment.srcAccessMask = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
        toAttachment.dstStageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        toAttachment.dstAccessMask = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
        toAttachment.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        toAttachment.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        toAttachment.image = image;
        toAttachment.subresourceRange = viewInfo.subresourceRange;
        VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dependency.imageMemoryBarrierCount = 1;
        dependency.pImageMemoryBarriers = &toAttachment;
        vkCmdPipelineBarrier2(cmd, &dependency);
        VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        color.imageView = view;
        color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        VkRenderingInfo pass{VK_STRUCTURE_TYPE_RENDERING_INFO};
        pass.renderArea = {{0, 0}, {16, 16}};
        pass.layerCount = 1;
        pass.colorAttachmentCount = 1;
        pass.pColorAttachments = &color;
        vkCmdBeginRendering(cmd, &pass);
        VkViewport vp{0.0f, 0.0f, 16.0f, 16.0f, 0.0f, 1.0f};
        VkRect2D scissor{{0, 0}, {16, 16}};
        vkCmdSetViewport(cmd, 0, 1, &vp);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vkCmdDraw(cmd, count, 1, 0, 0);
        vkCmdEndRendering(cmd);
        check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        check(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit");
        check(vkQueueWaitIdle(queue), "vkQueueWaitIdle");
    }

    vkDestroyCommandPool(device, pool, nullptr);
    vkDestroyPipeline(device, pipeline, nullptr);
    vkDestroyShaderModule(device, vert, nullptr);
    vkDestroyShaderModule(device, frag, nullptr);
    vkDestroyPipelineLayout(device, layout, nullptr);
    vkDestroyImageView(device, view, nullptr);
    vkDestroyImage(device, image, nullptr);
    vkFreeMemory(device, memory, nullptr);
    minimal::destroyDevice(vk);
    if (!cacheDir.empty())
        std::filesystem::remove_all(cacheDir);
    if (!std::getenv("VSC_WARMING"))
        std::printf("vs_store_check: drew %u..%u vertices on %s\n", first, last, vk.props.deviceName);
    return 0;
}
