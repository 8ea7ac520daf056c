// Flattening a tiling of filled Wang tiles into a field on the terrain, and resolving the
// overlaps that the terrain's heights create (field.h).
#include "placement/field.h"

#include "core/error.h"

#include <algorithm>
#include <string>

namespace meadow {

Field buildField(const WangTileFill& fill, std::span<const SweptVolume> clumps, std::span<const SweptVolume> rocks,
                 const Terrain& terrain, const FieldParams& params) {
    if (params.tilesX == 0 || params.tilesY == 0)
        throw Error("field: " + std::to_string(params.tilesX) + " x " + std::to_string(params.tilesY) +
                    " tiles is empty");
    if (clumps.empty())
        throw Error("field: the clump list is empty");
    for (std::span<const SweptVolume> volumes : {clumps, rocks})
        for (const SweptVolume& volume : volumes)
            if (volume.cellSize() != clumps[0].cellSize())
                throw Error("field: swept volumes differ in cell size");
    for (const TileContent& tile : fill.tiles) {
        for (const TilePlacement& p : tile.clumps)
            if (p.index >= clumps.size())
                throw Error("field: the tiles name clump " + std::to_string(p.index) + " of " +
                            std::to_string(clumps.size()));
        for (const TilePlacement& p : tile.rocks)
            if (p.index >= rocks.size())
                throw Error("field: the tiles name rock " + std::to_string(p.index) + " of " +
                            std::to_string(rocks.size()));
    }

    Field field;
    field.tilesX = params.tilesX;
    field.tilesY = params.tilesY;
    field.tileSize = fill.tileSize;
    field.windDirection = fill.windDirection;
    field.origin = -0.5f * glm::vec2(float(params.tilesX), float(params.tilesY)) * fill.tileSize;
    field.tiling = params.tiling == TilingMethod::Scanline
                       ? scanlineWangTiling(params.tilesX, params.tilesY, params.seed)
                       : hashWangTiling(0, 0, params.tilesX, params.tilesY, params.seed);

    auto place = [&](const TilePlacement& p, glm::vec2 corner) {
        const glm::vec2 xz = corner + p.position;
        return PlacedInstance{glm::vec3(xz.x, terrain.height(xz.x, xz.y), xz.y), p.yaw, p.index, p.mirrored};
    };
    for (uint32_t y = 0; y < params.tilesY; ++y)
        for (uint32_t x = 0; x < params.tilesX; ++x) {
            const TileContent& tile = fill.tiles[field.tiling.at(x, y)];
            const glm::vec2 corner = field.origin + glm::vec2(float(x), float(y)) * fill.tileSize;
            for (const TilePlacement& p : tile.clumps)
                field.clumps.push_back(place(p, corner));
            for (const TilePlacement& p : tile.rocks)
                field.rocks.push_back(place(p, corner));
        }

    const std::vector<std::pair<uint32_t, uint32_t>> pairs =
        findFieldOverlaps(field, clumps, rocks, &field.overlaps3d.candidatePairs);
    field.overlaps3d.pairsFound = uint32_t(pairs.size());
    if (!params.resolveOverlaps || pairs.empty()) {
        field.overlaps3d.pairsRemaining = uint32_t(pairs.size());
        return field;
    }

    // Drop the later instance of every overlapping pair whose earlier one is kept, in ascending
    // order of the later one: the same answer whatever order the pairs were found in.
    const size_t clumpCount = field.clumps.size(), total = clumpCount + field.rocks.size();
    std::vector<std::vector<uint32_t>> earlier(total);
    for (const auto& [i, j] : pairs)
        earlier[j].push_back(i);
    std::vector<uint8_t> keep(total, 1);
    for (size_t j = 0; j < total; ++j)
        keep[j] = std::none_of(earlier[j].begin(), earlier[j].end(), [&](uint32_t i) { return keep[i] != 0; });
    std::vector<PlacedInstance> keptClumps, keptRocks;
    for (size_t i = 0; i < total; ++i) {
        const bool isClump = i < clumpCount;
        const PlacedInstance& instance = isClump ? field.clumps[i] : field.rocks[i - clumpCount];
        if (keep[i])
            (isClump ? keptClumps : keptRocks).push_back(instance);
        else
            ++(isClump ? field.overlaps3d.clumpsRemoved : field.overlaps3d.rocksRemoved);
    }
    field.clumps = std::move(keptClumps);
    field.rocks = std::move(keptRocks);
    // A fresh check of the final field, not a count derived from the resolution.
    field.overlaps3d.pairsRemaining = uint32_t(findFieldOverlaps(field, clumps, rocks).size());
    return field;
}

} // namespace meadow
