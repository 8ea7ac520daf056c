// Barriers, derived in one place from what a pass reads or writes (synchronization2).
// A pass names its accesses with the Access presets below; barrier() turns a pair into the
// pipeline barrier that orders them.
#pragma once

#include <vulkan/vulkan.h>

namespace meadow {

struct Access {
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
};

namespace access {
inline constexpr Access kNone{VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE};
inline constexpr Access kAnyCommand{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                    VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};
inline constexpr Access kTransferWrite{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
inline constexpr Access kTransferRead{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
inline constexpr Access kComputeRead{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT};
inline constexpr Access kComputeReadWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
inline constexpr Access kComputeWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
inline constexpr Access kIndirectRead{VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT};
inline constexpr Access kVertexShaderRead{VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT};
inline constexpr Access kFragmentShaderRead{VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
inline constexpr Access kColorAttachmentWrite{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                              VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                                  VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT};
inline constexpr Access kDepthAttachment{
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
inline constexpr Access kHostRead{VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT};
inline constexpr Access kComputeSampledRead{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                            VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
} // namespace access

inline Access operator|(Access a, Access b) {
    return {a.stage | b.stage, a.access | b.access};
}

// Orders all memory accesses `before` against `after` (global memory barrier).
void barrier(VkCommandBuffer cmd, Access before, Access after);

// Orders accesses to one image and moves it from `oldLayout` to `newLayout`.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, Access before, VkImageLayout oldLayout,
                  Access after, VkImageLayout newLayout);

} // namespace meadow
