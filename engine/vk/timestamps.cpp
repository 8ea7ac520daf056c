#include "vk/timestamps.h"

#include "vk/context.h"
#include "vk/vk_check.h"

namespace meadow {

GpuTimer createGpuTimer(Context& ctx, uint32_t maxTimestamps) {
    GpuTimer t;
    t.capacity = maxTimestamps;
    t.nanosecondsPerTick = ctx.properties.limits.timestampPeriod;
    t.validMask = ctx.timestampValidBits >= 64 ? ~0ull : ((1ull << ctx.timestampValidBits) - 1);
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = maxTimestamps;
    VK_CHECK(vkCreateQueryPool(ctx.device, &info, nullptr, &t.pool));
    vkResetQueryPool(ctx.device, t.pool, 0, maxTimestamps);
    return t;
}

void destroyGpuTimer(Context& ctx, GpuTimer& t) {
    if (t.pool)
        vkDestroyQueryPool(ctx.device, t.pool, nullptr);
    t = GpuTimer{};
}

void beginTimestamps(Context& ctx, GpuTimer& t, VkCommandBuffer cmd) {
    vkResetQueryPool(ctx.device, t.pool, 0, t.capacity);
    t.used = 0;
    t.labels.clear();
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, t.pool, t.used++);
}

void markTimestamp(GpuTimer& t, VkCommandBuffer cmd, const std::string& label) {
    if (t.used >= t.capacity)
        throw Error("GPU timer: more than " + std::to_string(t.capacity) + " timestamps in one frame");
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, t.pool, t.used++);
    t.labels.push_back(label);
}

std::vector<PassTime> readTimestamps(Context& ctx, const GpuTimer& t) {
    std::vector<PassTime> out;
    if (t.used < 2)
        return out;
    std::vector<uint64_t> ticks(t.used);
    VK_CHECK(vkGetQueryPoolResults(ctx.device, t.pool, 0, t.used, ticks.size() * sizeof(uint64_t), ticks.data(),
                                   sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    for (uint32_t i = 1; i < t.used; ++i) {
        uint64_t delta = ((ticks[i] & t.validMask) - (ticks[i - 1] & t.validMask)) & t.validMask;
        out.push_back({t.labels[i - 1], static_cast<double>(delta) * t.nanosecondsPerTick * 1e-6});
    }
    return out;
}

} // namespace meadow
