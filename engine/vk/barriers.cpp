#include "vk/barriers.h"

namespace meadow {

void barrier(VkCommandBuffer cmd, Access before, Access after) {
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = before.stage;
    mb.srcAccessMask = before.access;
    mb.dstStageMask = after.stage;
    mb.dstAccessMask = after.access;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &mb;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, Access before, VkImageLayout oldLayout,
                  Access after, VkImageLayout newLayout) {
    VkImageMemoryBarrier2 ib{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    ib.srcStageMask = before.stage;
    ib.srcAccessMask = before.access;
    ib.dstStageMask = after.stage;
    ib.dstAccessMask = after.access;
    ib.oldLayout = oldLayout;
    ib.newLayout = newLayout;
    ib.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    ib.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    ib.image = image;
    ib.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &ib;
    vkCmdPipelineBarrier2(cmd, &dep);
}

} // namespace meadow
