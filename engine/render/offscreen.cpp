#include "render/offscreen.h"

#include "vk/context.h"
#include "vk/vk_check.h"

#include <chrono>

namespace meadow {

Offscreen createOffscreen(Context& ctx, VkExtent2D extent, HdrContents hdr) {
    Offscreen o;
    o.targets = createRenderTargets(ctx, extent, hdr);
    o.timer = createGpuTimer(ctx, 16);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = ctx.commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(ctx.device, &alloc, &o.cmd));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(ctx.device, &fenceInfo, nullptr, &o.fence));
    return o;
}

void destroyOffscreen(Context& ctx, Offscreen& o) {
    vkDeviceWaitIdle(ctx.device);
    vkDestroyFence(ctx.device, o.fence, nullptr);
    vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &o.cmd);
    destroyGpuTimer(ctx, o.timer);
    destroyRenderTargets(ctx, o.targets);
    o = Offscreen{};
}

FrameTimings renderOffscreenFrame(Context& ctx, FieldRenderer& renderer, Offscreen& o, const FrameState& state) {
    using Clock = std::chrono::steady_clock;
    auto start = Clock::now();
    updateFrame(ctx, renderer, state);
    VK_CHECK(vkResetCommandBuffer(o.cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(o.cmd, &begin));
    recordFieldFrame(ctx, renderer, o.cmd, o.targets, &o.timer);
    VK_CHECK(vkEndCommandBuffer(o.cmd));

    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = o.cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    VK_CHECK(vkQueueSubmit2(ctx.queue, 1, &submit, o.fence));
    auto submitted = Clock::now();
    VK_CHECK(vkWaitForFences(ctx.device, 1, &o.fence, VK_TRUE, UINT64_MAX));
    VK_CHECK(vkResetFences(ctx.device, 1, &o.fence));
    auto done = Clock::now();

    FrameTimings t;
    t.cpuRecordSubmitMs = std::chrono::duration<double, std::milli>(submitted - start).count();
    t.wallMs = std::chrono::duration<double, std::milli>(done - start).count();
    t.gpu = readTimestamps(ctx, o.timer);
    return t;
}

} // namespace meadow
