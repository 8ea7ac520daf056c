// Buffers and images, sub-allocated from large VkDeviceMemory blocks, plus upload and readback.
//
// The allocator keeps, per memory type, a list of blocks (kBlockSize each, or one block the size
// of a larger request), each with a first-fit RangeAllocator. Host-visible blocks stay mapped
// for their whole life. Every allocation is aligned to at least bufferImageGranularity so
// buffers and optimal-tiling images may share a block. Callers own what they create and destroy
// it before the context.
#pragma once

#include "vk/range_allocator.h"

#include <memory>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace meadow {

struct Context;

enum class MemoryUse {
    Device,   // device-local, filled by uploads or GPU passes
    Upload,   // host-visible and coherent, written by the CPU (uniforms, staging)
    Readback, // host-visible, preferably cached, read by the CPU
};

struct Allocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;
    uint32_t memoryType = 0;
    uint32_t block = 0;
    void* mapped = nullptr; // host pointer to this allocation when host-visible
};

class MemoryAllocator {
  public:
    static constexpr VkDeviceSize kBlockSize = 64ull << 20;

    explicit MemoryAllocator(Context& context);
    ~MemoryAllocator();
    MemoryAllocator(const MemoryAllocator&) = delete;
    MemoryAllocator& operator=(const MemoryAllocator&) = delete;

    Allocation allocate(const VkMemoryRequirements& requirements, MemoryUse use);
    void free(const Allocation& allocation);

    VkDeviceSize bytesInUse() const { return bytesInUse_; }

  private:
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        void* mapped = nullptr;
        std::unique_ptr<RangeAllocator> ranges;
    };
    uint32_t chooseMemoryType(uint32_t typeBits, MemoryUse use) const;

    Context& context_;
    std::vector<std::vector<Block>> blocks_; // [memoryType][block]
    VkDeviceSize bytesInUse_ = 0;
};

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    Allocation allocation;
    // A mapped buffer's bytes, to read. The CPU writes through writeMapped and hostWriteAt.
    const void* mapped() const { return allocation.mapped; }
};

struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    uint32_t mipLevels = 1;
    Allocation allocation;
};

Buffer createBuffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use);
void destroyBuffer(Context& context, Buffer& buffer);

// A view of a whole buffer (made with VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT) as texels of
// `format`, `texelBytes` each, for shaders that read it with texelFetch (a samplerBuffer). Throws
// meadow::Error naming `what` when the device cannot read that format so, or the buffer holds
// more texels than the device's maxTexelBufferElements. Destroy with vkDestroyBufferView.
VkBufferView createTexelBufferView(Context& context, const Buffer& buffer, VkFormat format, uint32_t texelBytes,
                                   const std::string& what);

Image createImage2D(Context& context, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                    uint32_t mipLevels = 1);
void destroyImage(Context& context, Image& image);

// Writes `size` bytes into a mapped (Upload or Readback) buffer at `offset`, counted in
// Context::hostBytesWritten, as every write of the CPU for the device is.
void writeMapped(Context& context, const Buffer& buffer, const void* data, VkDeviceSize size, VkDeviceSize offset = 0);
// Where to write `size` bytes of a mapped buffer at `offset` in place; counted as written.
void* hostWriteAt(Context& context, const Buffer& buffer, VkDeviceSize offset, VkDeviceSize size);

// Copies `size` bytes into a device-local buffer through a temporary staging buffer and waits.
void uploadToBuffer(Context& context, const Buffer& destination, const void* data, VkDeviceSize size,
                    VkDeviceSize destinationOffset = 0);
// A sampled texture from tightly packed texels of `texelBytes` each in `format`, with a full mip
// chain made by linear blits; left in SHADER_READ_ONLY_OPTIMAL for fragment shaders. Waits for the
// copy.
Image createTexture(Context& context, VkExtent2D extent, VkFormat format, const void* texels, uint32_t texelBytes);

// A trilinear sampler that clamps to the edge (atlas regions must not bleed across the border),
// reading mip levels up to `maxLod`.
VkSampler createLinearSampler(Context& context, float maxLod = VK_LOD_CLAMP_NONE);
// Point sampling, for images read texel by texel (texelFetch), such as depth.
VkSampler createNearestSampler(Context& context);
// A bilinear sampler for a lat-long panorama (one mip level): wraps around in u (azimuth), clamps
// to the edge in v (the poles).
VkSampler createPanoramaSampler(Context& context);

// Copies `size` bytes of a buffer back to host memory and waits.
void readbackBuffer(Context& context, const Buffer& source, void* data, VkDeviceSize size,
                    VkDeviceSize sourceOffset = 0);

} // namespace meadow
