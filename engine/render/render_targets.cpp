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

// Copies an image that the tonemap pass left in GENERAL layout into host memory.
std::vector<uint8_t> readImage(Context& ctx, const Image& image, uint32_t bytesPerPixel) {
    VkDeviceSize size = VkDeviceSize(image.extent.width) * image.extent.height * bytesPerPixel;
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
        imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kComputeReadWrite, VK_IMAGE_LAYOUT_GENERAL,
                     access::kTransferRead, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {image.extent.width, image.extent.height, 1};
        vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
        imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kTransferRead,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, access::kComputeReadWrite, VK_IMAGE_LAYOUT_GENERAL);
        barrier(cmd, access::kTransferWrite, access::kHostRead);
    });
    std::vector<uint8_t> pixels(size);
    std::memcpy(pixels.data(), staging.mapped(), size);
    destroyBuffer(ctx, staging);
    return pixels;
}

} // namespace

RenderTargets createRenderTargets(Context& ctx, VkExtent2D extent) {
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
    t.hdr = createImage2D(ctx, extent, kHdrFormat,
                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    t.depth = createImage2D(ctx, extent, kDepthFormat,
                            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                VK_IMAGE_USAGE_TRANSFER_SRC_BIT); // read back by tests (readFarDepth)
    t.ldr = createImage2D(ctx, extent, kLdrFormat, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    t.farVisibility = createBuffer(ctx, VkDeviceSize(extent.width) * extent.height * sizeof(uint64_t),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                       VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                   MemoryUse::Device);
    return t;
}

void destroyRenderTargets(Context& ctx, RenderTargets& t) {
    destroyImage(ctx, t.hdr);
    destroyImage(ctx, t.depth);
    destroyImage(ctx, t.ldr);
    destroyBuffer(ctx, t.farVisibility);
    t = RenderTargets{};
}

std::vector<uint8_t> readLdrPixels(Context& ctx, const RenderTargets& t) {
    return readImage(ctx, t.ldr, 4);
}

std::vector<float> readFarDepth(Context& ctx, const RenderTargets& t) {
    const VkDeviceSize size = VkDeviceSize(t.extent.width) * t.extent.height * sizeof(float);
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
        imageBarrier(cmd, t.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, access::kComputeSampledRead,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, access::kTransferRead,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
        region.imageExtent = {t.extent.width, t.extent.height, 1};
        vkCmdCopyImageToBuffer(cmd, t.depth.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
        imageBarrier(cmd, t.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, access::kTransferRead,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, access::kComputeSampledRead,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        barrier(cmd, access::kTransferWrite, access::kHostRead);
    });
    std::vector<float> depth(size / sizeof(float));
    std::memcpy(depth.data(), staging.mapped(), size);
    destroyBuffer(ctx, staging);
    return depth;
}

std::vector<uint64_t> readFarVisibility(Context& ctx, const RenderTargets& t) {
    std::vector<uint64_t> words(size_t(t.extent.width) * t.extent.height);
    readbackBuffer(ctx, t.farVisibility, words.data(), words.size() * sizeof(uint64_t));
    return words;
}

std::vector<uint16_t> readHdrPixels(Context& ctx, const RenderTargets& t) {
    std::vector<uint8_t> bytes = readImage(ctx, t.hdr, 8);
    std::vector<uint16_t> halves(bytes.size() / 2);
    std::memcpy(halves.data(), bytes.data(), bytes.size());
    return halves;
}

} // namespace meadow
