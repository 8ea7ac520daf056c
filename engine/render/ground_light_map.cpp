#include "render/ground_light_map.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace meadow {

GroundLightMapLayout groundLightMapLayout(std::span<const FieldClump> clumps,
                                          std::span<const gpu::GpuInstance> instances, uint64_t entryBudget) {
    glm::vec2 low(1e30f), high(-1e30f);
    double gridArea = 0.0; // m², over every grid: a grid covers about its area / texel² texels
    for (const gpu::GpuInstance& inst : instances) {
        if (clumps[inst.mesh].groundResolution < 2)
            continue;
        const float side = clumps[inst.mesh].groundSize * std::abs(inst.positionScale.w);
        const float reach = 0.75f * side; // > half the diagonal
        gridArea += double(side) * double(side);
        low = glm::min(low, glm::vec2(inst.positionScale.x, inst.positionScale.z) - reach);
        high = glm::max(high, glm::vec2(inst.positionScale.x, inst.positionScale.z) + reach);
    }
    GroundLightMapLayout map;
    if (low.x < high.x) {
        const glm::vec2 extent = high - low;
        const float texel =
            std::max(kGroundMapFinestTexel, float(std::sqrt(gridArea / double(std::max<uint64_t>(entryBudget, 1)))));
        map.size = {std::clamp(uint32_t(extent.x / texel), 16u, 2048u),
                    std::clamp(uint32_t(extent.y / texel), 16u, 2048u)};
        map.rect = glm::vec4(low, 1.0f / extent.x, 1.0f / extent.y);
    } else {
        map.rect = glm::vec4(0.0f, 0.0f, 0.0f, 0.0f); // nothing casts: every point reads the open-ground texel
    }
    return map;
}

namespace {

// The cell of a grid point g inside the grid (0 .. last on both axes), and where g lies in it.
struct GridCell {
    uint32_t column, row;
    glm::vec2 weight;
};
GridCell cellAt(glm::vec2 g, float last) {
    const glm::vec2 cell = glm::min(glm::floor(g), glm::vec2(last - 1.0f));
    return {uint32_t(cell.x), uint32_t(cell.y), g - cell};
}

bool insideGrid(glm::vec2 g, float last) {
    return g.x >= 0.0f && g.y >= 0.0f && g.x <= last && g.y <= last;
}

} // namespace

glm::vec2 groundGridPoint(const GroundCaster& caster, glm::vec2 at) {
    return glm::vec2(0.5f * float(caster.points - 1)) + caster.toGrid * (at - caster.base);
}

// The instance's grid point p (clump space, y up, x and z in [-side/2, side/2]) lies at world
// base + R(yaw) M p |scale| (instance.vert: M the mirror when the scale is negative), at grid
// coordinates (p / side + 1/2) (points - 1); a map point t (texels) at world rect.xy + t / texelsPerMetre.
std::vector<GroundCaster> groundCasters(std::span<const gpu::GpuClump> clumps,
                                        std::span<const gpu::GpuInstance> instances, const GroundLightMapLayout& layout,
                                        glm::vec2 mirrorNormal) {
    std::vector<GroundCaster> casters;
    if (layout.rect.z == 0.0f)
        return casters; // nothing casts: the map stays open ground
    const glm::vec2 texelsPerMetre(float(layout.size.width) * layout.rect.z, float(layout.size.height) * layout.rect.w);
    const glm::mat2 toTexels(glm::vec2(texelsPerMetre.x, 0.0f), glm::vec2(0.0f, texelsPerMetre.y));
    const glm::mat2 mirror = glm::mat2(1.0f) - 2.0f * glm::outerProduct(mirrorNormal, mirrorNormal);
    for (const gpu::GpuInstance& inst : instances) {
        const gpu::GpuClump& clump = clumps[inst.mesh];
        GroundCaster c;
        c.points = clump.ground.z;
        if (c.points < 2)
            continue;
        if (c.points > gpu::kGroundGridMaxPoints)
            throw Error("field clump " + std::to_string(inst.mesh) + ": its ground grid has " +
                        std::to_string(c.points) + " points a side; the renderer takes at most " +
                        std::to_string(gpu::kGroundGridMaxPoints));
        const float side = clump.yawBins.w, scale = std::abs(inst.positionScale.w);
        c.base = (glm::vec2(inst.positionScale.x, inst.positionScale.z) - glm::vec2(layout.rect.x, layout.rect.y)) *
                 texelsPerMetre;
        // R maps clump offsets (x, z) to world offsets (c x + s z, -s x + c z), as instance.vert turns.
        const float sine = std::sin(inst.yaw), cosine = std::cos(inst.yaw);
        const glm::mat2 turn(glm::vec2(cosine, -sine), glm::vec2(sine, cosine)); // columns
        const bool mirrored = inst.positionScale.w < 0.0f;
        const glm::mat2 m = mirrored ? mirror : glm::mat2(1.0f);
        c.toGrid = float(c.points - 1) / (side * scale) * m * glm::transpose(turn) * glm::inverse(toTexels);
        c.first = clump.ground.y + gpu::lightVariant(inst, clump) * c.points * c.points;
        c.low = glm::vec2(1e30f);
        c.high = glm::vec2(-1e30f);
        for (int corner = 0; corner < 4; ++corner) {
            const glm::vec2 p(corner & 1 ? 0.5f * side : -0.5f * side, corner & 2 ? 0.5f * side : -0.5f * side);
            const glm::vec2 texel = c.base + toTexels * (turn * (m * p)) * scale;
            c.low = glm::min(c.low, texel);
            c.high = glm::max(c.high, texel);
        }
        casters.push_back(c);
    }
    return casters;
}

namespace {

// Calls visit(texel index, cell) for every texel centre inside the caster's grid, row by row.
template <typename Visit> void forEachCoveredTexel(const GroundCaster& c, VkExtent2D size, Visit&& visit) {
    // A texel's centre x + 1/2 inside [low, high] has x in [low - 1/2, high - 1/2]; a thousandth of a
    // texel more each way, so that rounding in the corners never drops a centre that
    // groundGridPoint, which decides, puts on the grid's edge.
    const glm::ivec2 last(int(size.width) - 1, int(size.height) - 1);
    const glm::ivec2 low = glm::clamp(glm::ivec2(glm::ceil(c.low - 0.501f)), glm::ivec2(0), last);
    const glm::ivec2 high = glm::clamp(glm::ivec2(glm::floor(c.high - 0.499f)), glm::ivec2(-1), last);
    const float lastPoint = float(c.points - 1);
    for (int y = low.y; y <= high.y; ++y)
        for (int x = low.x; x <= high.x; ++x) {
            const glm::vec2 g = groundGridPoint(c, glm::vec2(float(x) + 0.5f, float(y) + 0.5f));
            if (insideGrid(g, lastPoint))
                visit(size_t(y) * size.width + size_t(x), cellAt(g, lastPoint));
        }
}

} // namespace

GroundLightMapLists groundLightMapLists(std::span<const GroundCaster> casters, VkExtent2D size) {
    GroundLightMapLists out;
    out.size = size;
    const size_t texels = size_t(size.width) * size.height;
    out.texelStart.assign(texels + 1, 0);
    // A counting sort by texel that keeps the caster order: count, then place.
    for (const GroundCaster& c : casters)
        forEachCoveredTexel(c, size, [&](size_t texel, const GridCell&) { ++out.texelStart[texel + 1]; });
    uint64_t total = 0;
    for (size_t t = 0; t < texels; ++t) {
        total += out.texelStart[t + 1];
        if (total >= (uint64_t(1) << 32))
            throw Error("the ground light map's texels list more than 2^32 grid cells");
        out.texelStart[t + 1] = uint32_t(total);
    }
    out.entries.resize(total);
    std::vector<uint32_t> next(out.texelStart.begin(), out.texelStart.end() - 1);
    const float unit = float((1u << gpu::kGroundWeightBits) - 1u);
    for (const GroundCaster& c : casters)
        forEachCoveredTexel(c, size, [&](size_t texel, const GridCell& cell) {
            const uint32_t wx = uint32_t(std::lround(cell.weight.x * unit));
            const uint32_t wz = uint32_t(std::lround(cell.weight.y * unit));
            out.entries[next[texel]++] =
                glm::uvec2(c.first + cell.row * c.points + cell.column,
                           wx | wz << gpu::kGroundWeightBits | (c.points - 1) << (2 * gpu::kGroundWeightBits));
        });
    return out;
}

std::vector<glm::vec3> groundLightMapReference(std::span<const GroundCaster> casters, VkExtent2D size,
                                               std::span<const glm::uvec4> vertexLight) {
    std::vector<glm::vec3> map(size_t(size.width) * size.height, glm::vec3(1.0f));
    auto ratio = [&](uint32_t texel) {
        if (texel >= vertexLight.size())
            throw Error("a ground caster reads vertex light " + std::to_string(texel) + " of " +
                        std::to_string(vertexLight.size()));
        const glm::uvec4 v = vertexLight[texel];
        return glm::uintBitsToFloat(glm::uvec3(v));
    };
    for (const GroundCaster& c : casters) {
        const float last = float(c.points - 1);
        for (uint32_t y = 0; y < size.height; ++y)
            for (uint32_t x = 0; x < size.width; ++x) {
                const glm::vec2 g = groundGridPoint(c, glm::vec2(float(x) + 0.5f, float(y) + 0.5f));
                if (!insideGrid(g, last))
                    continue;
                const GridCell cell = cellAt(g, last);
                const uint32_t corner = c.first + cell.row * c.points + cell.column;
                const glm::vec3 r00 = ratio(corner), r10 = ratio(corner + 1);
                const glm::vec3 r01 = ratio(corner + c.points), r11 = ratio(corner + c.points + 1);
                map[size_t(y) * size.width + x] *=
                    glm::mix(glm::mix(r00, r10, cell.weight.x), glm::mix(r01, r11, cell.weight.x), cell.weight.y);
            }
    }
    return map;
}

} // namespace meadow
