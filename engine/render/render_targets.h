// The images one frame renders into: linear HDR colour, reversed-Z depth, and the tonemapped
// 8-bit image that is written to PNG or blitted to a window; and the far field's visibility
// buffer.
#pragma once

#include "vk/barriers.h"
#include "vk/memory.h"

#include <cstdint>
#include <vector>

namespace meadow {

inline constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr VkFormat kLdrFormat = VK_FORMAT_R8G8B8A8_UNORM; // values already sRGB-encoded

// What the HDR image holds once a frame is done. `Frame`: the whole frame, as the LDR image shows
// it before tone mapping (EXR output and the tests read it). `MeshPass`: only what the mesh pass
// drew; the far field's and the near raster's pixels go to the LDR image alone. Nothing the bench
// or the window does reads the HDR image after the frame, and without that store the resolve pass
// takes about 3 ms less on lavapipe (docs/BENCHMARKS.md). The LDR image is the same either way.
enum class HdrContents { Frame, MeshPass };

struct RenderTargets {
    VkExtent2D extent{};
    HdrContents hdrContents = HdrContents::Frame;
    Image hdr;
    Image depth; // also sampled: the far field's splats are tested against it
    Image ldr;
    // The far field's visibility buffer: per pixel one 64-bit word (far_splat.h), row-major. The
    // passes that merge into it use atomics on the storage buffer; the resolve reads it through an
    // R32G32_UINT texel view, one gather where llvmpipe loads a storage buffer lane by lane.
    Buffer farVisibility;
    VkBufferView farVisibilityTexels = VK_NULL_HANDLE;
};

// Throws meadow::Error when the device cannot use the formats as meadow needs.
RenderTargets createRenderTargets(Context& context, VkExtent2D extent, HdrContents hdr = HdrContents::Frame);
void destroyRenderTargets(Context& context, RenderTargets& targets);

// Pixels of the frame just rendered, after its commands completed: 8-bit RGBA (tonemapped) or
// half-float RGBA (linear HDR; throws meadow::Error for targets whose HDR image holds only the mesh
// pass). Records and waits on its own command buffer.
std::vector<uint8_t> readLdrPixels(Context& context, const RenderTargets& targets);
std::vector<uint16_t> readHdrPixels(Context& context, const RenderTargets& targets);
// After a frame with the far field (tests: the splat pass's CPU reference): the depth the mesh
// pass left for the splats (reversed Z, row-major), and the visibility buffer the splat pass left.
std::vector<float> readFarDepth(Context& context, const RenderTargets& targets);
std::vector<uint64_t> readFarVisibility(Context& context, const RenderTargets& targets);

// Any image's pixels (`aspect`, tightly packed rows), left in `layout` after `lastAccess`, as it
// was; records and waits on its own command buffer.
std::vector<uint8_t> readImageBytes(Context& context, const Image& image, VkImageAspectFlags aspect,
                                    uint32_t bytesPerPixel, VkImageLayout layout, Access lastAccess);

} // namespace meadow
