#include "vk/memory.h"

#include "core/error.h"
#include "vk/barriers.h"
#include "vk/context.h"
#include "vk/vk_check.h"

#include <algorithm>
#include <cassert>
#include <cstring>

namespace meadow {

MemoryAllocator::MemoryAllocator(Context& context) : context_(context) {
    blocks_.resize(context.memoryProperties.memoryTypeCount);
}

MemoryAllocator::~MemoryAllocator() {
    for (auto& typeBlocks : blocks_)
        for (Block& block : typeBlocks)
            if (block.memory)
                vkFreeMemory(context_.device, block.memory, nullptr);
}

uint32_t MemoryAllocator::chooseMemoryType(uint32_t typeBits, MemoryUse use) const {
    const VkPhysicalDeviceMemoryProperties& mp = context_.memoryProperties;
    VkMemoryPropertyFlags required = 0;
    VkMemoryPropertyFlags preferred = 0;
    switch (use) {
    case MemoryUse::Device: preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
    case MemoryUse::Upload:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        break;
    case MemoryUse::Readback:
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
        break;
    }
    int fallback = -1;
    for (uint32_t i = 0; i < mp.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i)) || (mp.memoryTypes[i].propertyFlags & required) != required)
            continue;
        if ((mp.memoryTypes[i].propertyFlags & preferred) == preferred)
            return i;
        if (fallback < 0)
            fallback = static_cast<int>(i);
    }
    if (fallback < 0)
        throw Error("no Vulkan memory type fits a resource (type bits " + std::to_string(typeBits) + ")");
    return static_cast<uint32_t>(fallback);
}

Allocation MemoryAllocator::allocate(const VkMemoryRequirements& req, MemoryUse use) {
    uint32_t type = chooseMemoryType(req.memoryTypeBits, use);
    VkDeviceSize alignment = std::max<VkDeviceSize>(req.alignment, context_.properties.limits.bufferImageGranularity);
    VkMemoryPropertyFlags flags = context_.memoryProperties.memoryTypes[type].propertyFlags;
    if (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
        alignment = std::max<VkDeviceSize>(alignment, context_.properties.limits.nonCoherentAtomSize);

    std::vector<Block>& typeBlocks = blocks_[type];
    for (uint32_t b = 0; b < typeBlocks.size(); ++b) {
        Block& block = typeBlocks[b];
        if (!block.memory)
            continue;
        if (auto offset = block.ranges->allocate(req.size, alignment)) {
            bytesInUse_ += req.size;
            return {block.memory, *offset, req.size,
                    type,         b,       block.mapped ? static_cast<char*>(block.mapped) + *offset : nullptr};
        }
    }

    Block block;
    VkDeviceSize size = std::max(kBlockSize, req.size);
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = size;
    info.memoryTypeIndex = type;
    VkResult r = vkAllocateMemory(context_.device, &info, nullptr, &block.memory);
    if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw Error("out of memory allocating a " + std::to_string(size >> 20) + " MiB Vulkan memory block (" +
                    vkResultName(r) + ")");
    VK_CHECK(r);
    if (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
        VK_CHECK(vkMapMemory(context_.device, block.memory, 0, VK_WHOLE_SIZE, 0, &block.mapped));
    block.ranges = std::make_unique<RangeAllocator>(size);
    [[maybe_unused]] auto offset = block.ranges->allocate(req.size, alignment);
    assert(offset && *offset == 0);

    // Reuse a slot freed earlier so block indices held by live allocations stay valid.
    uint32_t index = 0;
    while (index < typeBlocks.size() && typeBlocks[index].memory)
        ++index;
    if (index == typeBlocks.size())
        typeBlocks.push_back(std::move(block));
    else
        typeBlocks[index] = std::move(block);
    Block& placed = typeBlocks[index];
    bytesInUse_ += req.size;
    return {placed.memory, 0, req.size, type, index, placed.mapped};
}

void MemoryAllocator::free(const Allocation& a) {
    if (!a.memory)
        return;
    Block& block = blocks_[a.memoryType][a.block];
    assert(block.memory == a.memory);
    block.ranges->free(a.offset, a.size);
    bytesInUse_ -= a.size;
    // A block larger than the standard size served one big resource: give it back at once.
    if (block.ranges->empty() && block.ranges->size() > kBlockSize) {
        vkFreeMemory(context_.device, block.memory, nullptr);
        block = Block{};
    }
}

Buffer createBuffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use) {
    Buffer buffer;
    buffer.size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VK_CHECK(vkCreateBuffer(ctx.device, &info, nullptr, &buffer.buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx.device, buffer.buffer, &req);
    buffer.allocation = ctx.memory->allocate(req, use);
    VK_CHECK(vkBindBufferMemory(ctx.device, buffer.buffer, buffer.allocation.memory, buffer.allocation.offset));
    return buffer;
}

VkBufferView createTexelBufferView(Context& ctx, const Buffer& buffer, VkFormat format, uint32_t texelBytes,
                                   const std::string& what) {
    VkFormatProperties properties;
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice, format, &properties);
    if (!(properties.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT))
        throw Error(what + ": the device cannot read format " + std::to_string(int(format)) +
                    " from a uniform texel buffer");
    const uint64_t texels = buffer.size / texelBytes;
    if (texels > ctx.properties.limits.maxTexelBufferElements)
        throw Error(what + ": " + std::to_string(texels) + " texels, more than the device's maxTexelBufferElements (" +
                    std::to_string(ctx.properties.limits.maxTexelBufferElements) + ")");
    VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    info.buffer = buffer.buffer;
    info.format = format;
    info.offset = 0;
    info.range = texels * texelBytes;
    VkBufferView view = VK_NULL_HANDLE;
    VK_CHECK(vkCreateBufferView(ctx.device, &info, nullptr, &view));
    return view;
}

void destroyBuffer(Context& ctx, Buffer& buffer) {
    if (buffer.buffer)
        vkDestroyBuffer(ctx.device, buffer.buffer, nullptr);
    ctx.memory->free(buffer.allocation);
    buffer = Buffer{};
}

Image createImage2D(Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage, uint32_t mipLevels) {
    Image image;
    image.format = format;
    image.extent = extent;
    image.mipLevels = mipLevels;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {extent.width, extent.height, 1};
    info.mipLevels = mipLevels;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VK_CHECK(vkCreateImage(ctx.device, &info, nullptr, &image.image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device, image.image, &req);
    image.allocation = ctx.memory->allocate(req, MemoryUse::Device);
    VK_CHECK(vkBindImageMemory(ctx.device, image.image, image.allocation.memory, image.allocation.offset));

    bool depth = format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM;
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image.image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format;
    viewInfo.subresourceRange = {
        static_cast<VkImageAspectFlags>(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, mipLevels, 0,
        1};
    VK_CHECK(vkCreateImageView(ctx.device, &viewInfo, nullptr, &image.view));
    return image;
}

void destroyImage(Context& ctx, Image& image) {
    if (image.view)
        vkDestroyImageView(ctx.device, image.view, nullptr);
    if (image.image)
        vkDestroyImage(ctx.device, image.image, nullptr);
    ctx.memory->free(image.allocation);
    image = Image{};
}

void* hostWriteAt(Context& ctx, const Buffer& buffer, VkDeviceSize offset, VkDeviceSize size) {
    if (!buffer.allocation.mapped || offset + size > buffer.size)
        throw Error("a host write of " + std::to_string(size) + " bytes at " + std::to_string(offset) +
                    " into a buffer of " + std::to_string(buffer.size) +
                    (buffer.allocation.mapped ? "" : " (not mapped)"));
    ctx.hostBytesWritten += size;
    return static_cast<char*>(buffer.allocation.mapped) + offset;
}

void writeMapped(Context& ctx, const Buffer& buffer, const void* data, VkDeviceSize size, VkDeviceSize offset) {
    std::memcpy(hostWriteAt(ctx, buffer, offset, size), data, size);
}

void uploadToBuffer(Context& ctx, const Buffer& destination, const void* data, VkDeviceSize size,
                    VkDeviceSize destinationOffset) {
    if (size == 0)
        return;
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload);
    writeMapped(ctx, staging, data, size);
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
        // Earlier submissions may still read or write the destination; later ones may use it
        // in any way.
        barrier(cmd, access::kAnyCommand, access::kTransferWrite);
        VkBufferCopy region{0, destinationOffset, size};
        vkCmdCopyBuffer(cmd, staging.buffer, destination.buffer, 1, &region);
        barrier(cmd, access::kTransferWrite, access::kAnyCommand);
    });
    destroyBuffer(ctx, staging);
}

Image createTexture(Context& ctx, VkExtent2D extent, VkFormat format, const void* texels, uint32_t texelBytes) {
    uint32_t mips = 1;
    while ((extent.width >> mips) > 0 || (extent.height >> mips) > 0)
        ++mips;
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice, format, &props);
    const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                                        VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                        VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    if ((props.optimalTilingFeatures & needed) != needed)
        throw Error("the Vulkan device cannot sample and blit the texture format meadow uses");
    Image image = createImage2D(
        ctx, extent, format,
        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, mips);
    VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * texelBytes;
    Buffer staging = createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload);
    writeMapped(ctx, staging, texels, bytes);
    const Access sampled{VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
        auto mipBarrier = [&](uint32_t mip, Access before, VkImageLayout from, Access after, VkImageLayout to) {
            VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
            b.srcStageMask = before.stage;
            b.srcAccessMask = before.access;
            b.dstStageMask = after.stage;
            b.dstAccessMask = after.access;
            b.oldLayout = from;
            b.newLayout = to;
            b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.image = image.image;
            b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 1, 0, 1};
            VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
            dep.imageMemoryBarrierCount = 1;
            dep.pImageMemoryBarriers = &b;
            vkCmdPipelineBarrier2(cmd, &dep);
        };
        for (uint32_t mip = 0; mip < mips; ++mip)
            mipBarrier(mip, access::kNone, VK_IMAGE_LAYOUT_UNDEFINED, access::kTransferWrite,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {extent.width, extent.height, 1};
        vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        // Each level is a linear downsample of the one above it.
        for (uint32_t mip = 1; mip < mips; ++mip) {
            mipBarrier(mip - 1, access::kTransferWrite, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, access::kTransferRead,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip - 1, 0, 1};
            blit.srcOffsets[1] = {int32_t(std::max(1u, extent.width >> (mip - 1))),
                                  int32_t(std::max(1u, extent.height >> (mip - 1))), 1};
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 0, 1};
            blit.dstOffsets[1] = {int32_t(std::max(1u, extent.width >> mip)),
                                  int32_t(std::max(1u, extent.height >> mip)), 1};
            vkCmdBlitImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.image,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
            mipBarrier(mip - 1, access::kTransferRead, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, sampled,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        }
        mipBarrier(mips - 1, access::kTransferWrite, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, sampled,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
    destroyBuffer(ctx, staging);
    return image;
}

namespace {

// meadow's samplers differ in their filter, how u is addressed and their mip range; v and w clamp
// to the edge.
VkSampler createSampler(Context& ctx, VkFilter filter, VkSamplerMipmapMode mipmap, VkSamplerAddressMode u,
                        float maxLod) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = filter;
    info.mipmapMode = mipmap;
    info.addressModeU = u;
    info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.maxLod = maxLod;
    VkSampler sampler;
    VK_CHECK(vkCreateSampler(ctx.device, &info, nullptr, &sampler));
    return sampler;
}

} // namespace

VkSampler createLinearSampler(Context& ctx, float maxLod) {
    return createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                         maxLod);
}

VkSampler createNearestSampler(Context& ctx) {
    return createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                         0.0f);
}

VkSampler createPanoramaSampler(Context& ctx) {
    return createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT, 0.0f);
}

void readbackBuffer(Context& ctx, const Buffer& source, void* data, VkDeviceSize size, VkDeviceSize sourceOffset) {
    if (size == 0)
        return;
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
        barrier(cmd, access::kAnyCommand, access::kTransferRead);
        VkBufferCopy region{sourceOffset, 0, size};
        vkCmdCopyBuffer(cmd, source.buffer, staging.buffer, 1, &region);
        barrier(cmd, access::kTransferWrite, access::kHostRead);
    });
    std::memcpy(data, staging.mapped(), size);
    destroyBuffer(ctx, staging);
}

} // namespace meadow
