#include "render/render_targets.h"

#include "vk/barriers.h"
#include "vk/context.h"
#include "vk/vk_check.h"

#include <cstring>

namespace meadow {
namespace {

void requireFormat(Context& ctx, VkFormat format, VkFormatFeatureFlags features, const char* what) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice, format, &props);
    if ((props.optimalTilingFeatures & features) != features)
        throw Error(std::string("the Vulkan device cannot use the ") + what + " format as meadow needs");
}

} // namespace

std::vector<uint8_t> readImageBytes(Context& ctx, const Image& image, VkImageAspectFlags aspect, uint32_t bytesPerPixel,
                                    VkImageLayout layout, Access lastAccess) {
    const VkDeviceSize size = VkDeviceSize(image.extent.width) * image.extent.height * bytesPerPixel;
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
        imageBarrier(cmd, image.image, aspect, lastAccess, layout, access::kTransferRead,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy region{};
        region.imageSubresource = {aspect, 0, 0, 1};
        region.imageExtent = {image.extent.width, image.extent.height, 1};
        vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
        imageBarrier(cmd, image.image, aspect, access::kTransferRead, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, lastAccess,
                     layout);
        barrier(cmd, access::kTransferWrite, access::kHostRead);
    });
    std::vector<uint8_t> bytes(size);
    std::memcpy(bytes.data(), staging.mapped(), size);
    destroyBuffer(ctx, staging);
    return bytes;
}

RenderTargets createRenderTargets(Context& ctx, VkExtent2D extent, HdrContents hdr) {
    requireFormat(ctx, kHdrFormat,
                  VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT |
                      VK_FORMAT_FEATURE_TRANSFER_SRC_BIT,
                  "HDR colour (R16G16B16A16_SFLOAT)");
    requireFormat(ctx, kDepthFormat,
                  VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                      VK_FORMAT_FEATURE_TRANSFER_SRC_BIT,
                  "depth (D32_SFLOAT)");
    requireFormat(ctx, kLdrFormat,
                  VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT |
                      VK_FORMAT_FEATURE_BLIT_SRC_BIT,
                  "display (R8G8B8A8_UNORM)");
    RenderTargets t;
    t.extent = extent;
    t.hdrContents = hdr;
    t.hdr = createImage2D(ctx, extent, kHdrFormat,
                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    t.depth = createImage2D(ctx, extent, kDepthFormat,
                            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                VK_IMAGE_USAGE_TRANSFER_SRC_BIT); // read back by tests (readFarDepth)
    t.ldr = createImage2D(ctx, extent, kLdrFormat, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    t.farVisibility = createBuffer(ctx, VkDeviceSize(extent.width) * extent.height * sizeof(uint64_t),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                       VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                   MemoryUse::Device);
    t.farVisibilityTexels =
        createTexelBufferView(ctx, t.farVisibility, VK_FORMAT_R32G32_UINT, 8, "the visibility buffer");
    return t;
}

void destroyRenderTargets(Context& ctx, RenderTargets& t) {
    destroyImage(ctx, t.hdr);
    destroyImage(ctx, t.depth);
    destroyImage(ctx, t.ldr);
    if (t.farVisibilityTexels)
        vkDestroyBufferView(ctx.device, t.farVisibilityTexels, nullptr);
    destroyBuffer(ctx, t.farVisibility);
    t = RenderTargets{};
}

std::vector<uint8_t> readLdrPixels(Context& ctx, const RenderTargets& t) {
    return readImageBytes(ctx, t.ldr, VK_IMAGE_ASPECT_COLOR_BIT, 4, VK_IMAGE_LAYOUT_GENERAL, access::kComputeReadWrite);
}

std::vector<float> readFarDepth(Context& ctx, const RenderTargets& t) {
    const std::vector<uint8_t> bytes =
        readImageBytes(ctx, t.depth, VK_IMAGE_ASPECT_DEPTH_BIT, sizeof(float), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                       access::kComputeSampledRead);
    std::vector<float> depth(bytes.size() / sizeof(float));
    std::memcpy(depth.data(), bytes.data(), bytes.size());
    return depth;
}

std::vector<uint64_t> readFarVisibility(Context& ctx, const RenderTargets& t) {
    std::vector<uint64_t> words(size_t(t.extent.width) * t.extent.height);
    readbackBuffer(ctx, t.farVisibility, words.data(), words.size() * sizeof(uint64_t));
    return words;
}

std::vector<uint16_t> readHdrPixels(Context& ctx, const RenderTargets& t) {
    if (t.hdrContents != HdrContents::Frame)
        throw Error("the HDR image of these render targets holds only the mesh pass, not the frame (they were made "
                    "for the LDR image alone)");
    const std::vector<uint8_t> bytes =
        readImageBytes(ctx, t.hdr, VK_IMAGE_ASPECT_COLOR_BIT, 8, VK_IMAGE_LAYOUT_GENERAL, access::kComputeReadWrite);
    std::vector<uint16_t> halves(bytes.size() / 2);
    std::memcpy(halves.data(), bytes.data(), bytes.size());
    return halves;
}

} // namespace meadow
