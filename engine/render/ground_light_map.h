// The ground light map: the share of open-ground light that reaches each point of the field's
// ground, the product over every instance whose ground grid covers the point of that grid's
// shaded/open ratio (bilinear between its points; the light pass writes the ratios per variant
// into vertexLight when the sky moves). The terrain's fragment shader multiplies it in.
//
// The instances never move, so all but the ratios is laid out once, when the field is loaded:
// each instance's "caster" (where its grid lies on the map, and where its variant's ratios lie),
// and from the casters, per map texel, the list of grid cells whose grid covers the texel's
// centre, with the bilinear weights there, in instance order. ground_map.comp then gathers: one
// thread per texel multiplies in its list in order, with no atomics, so the same ratios give the
// same bytes, and no thread looks at a grid that misses its texel. (It replaced one quad per
// instance drawn with a multiplying blend: at a million clumps that was 7 ms on an H100 and half a
// second on lavapipe, all of it the graphics front end; docs/BENCHMARKS.md.)
#pragma once

#include "gpu_types.h"
#include "render/field_renderer.h"

#include <cstdint>
#include <span>
#include <vector>
#include <vulkan/vulkan.h>

namespace meadow {

// The gather's cost is its list entries, about one per texel that each grid covers: the texel is
// 8 cm, or as much coarser as keeps the lists near this many entries. The default field lists
// 5.0 M at 8 cm (4.2 M at 8.7 cm under this budget); a million clumps listed about 9.6 M at the
// 2048 texels' cap, a 0.12 ms gather on an H200 that took the frames running the light pass past
// the compute passes' 0.25 ms (docs/BENCHMARKS.md, 2026-11-28).
inline constexpr uint64_t kGroundMapEntryBudget = uint64_t(4) << 20;
inline constexpr float kGroundMapFinestTexel = 0.08f; // m

// A texel about every 8 cm over every instance's ground grid (16 to 2048 a side), coarser where
// the grids would list more than entryBudget entries, and its rectangle as GpuFrame::groundMap:
// x, y the lowest world x and z, z, w 1 / the size in x and z (all zero when no clump casts on the
// ground: then the map is one open-ground texel).
struct GroundLightMapLayout {
    VkExtent2D size{1, 1};
    glm::vec4 rect{0.0f};
};
GroundLightMapLayout groundLightMapLayout(std::span<const FieldClump> clumps,
                                          std::span<const gpu::GpuInstance> instances,
                                          uint64_t entryBudget = kGroundMapEntryBudget);

// One instance laying its clump's grid on the map. A point of the map in texels (texel (x, y)'s
// centre is (x + 1/2, y + 1/2)) lies at grid coordinates (points - 1) / 2 + toGrid (at - base):
// 0 .. points - 1 inside the grid. low and high bound the grid's square on the map.
struct GroundCaster {
    glm::vec2 base{0.0f};
    glm::mat2 toGrid{1.0f};
    uint32_t first = 0;  // the first vec4 of its variant's ratios in vertexLight, row by row
    uint32_t points = 0; // grid points per side, 2 .. gpu::kGroundGridMaxPoints
    glm::vec2 low{0.0f}, high{0.0f};
};
glm::vec2 groundGridPoint(const GroundCaster& caster, glm::vec2 at);

// The casters of every instance whose clump has a ground grid, in instance order, from the packed
// clumps (where each variant's ratios lie: GpuClump::ground, light, yawBins) and the plane the
// mirrored instances reflect about (FieldRenderer::mirrorNormal). A grid of more than
// gpu::kGroundGridMaxPoints a side is a meadow::Error naming its clump.
std::vector<GroundCaster> groundCasters(std::span<const gpu::GpuClump> clumps,
                                        std::span<const gpu::GpuInstance> instances, const GroundLightMapLayout& layout,
                                        glm::vec2 mirrorNormal);

// What ground_map.comp reads, all static: texelStart[t] .. texelStart[t + 1] the range of
// `entries` that texel t = y * width + x multiplies in, each a grid cell (the layout is
// gpu::kGroundEntry*). Throws meadow::Error when the lists would pass 2^32 entries.
struct GroundLightMapLists {
    std::vector<uint32_t> texelStart; // width * height + 1
    std::vector<glm::uvec2> entries;
    VkExtent2D size{1, 1};
};
GroundLightMapLists groundLightMapLists(std::span<const GroundCaster> casters, VkExtent2D size);

// The CPU reference of ground_map.comp: every texel's RGB ratio, row by row, from every caster in
// order (not from the lists, so that a list missing a cell shows; weights in full precision), the
// ratios read from the light pass's vertexLight as the shader reads them (float bits in xyz).
std::vector<glm::vec3> groundLightMapReference(std::span<const GroundCaster> casters, VkExtent2D size,
                                               std::span<const glm::uvec4> vertexLight);

} // namespace meadow
