// Voxel dart throwing into the complete Wang tile set (tile_fill.h).
#include "placement/tile_fill.h"

#include "core/error.h"
#include "placement/dart_throwing.h"
#include "placement/occupancy_grid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <limits>

namespace meadow {

// ---- Shared with the Poisson-disc baseline (dart_throwing.h) ------------------------------------

DartStream::DartStream(const TileFillParams& params, uint32_t tile, DartKind kind, uint32_t volumeCount)
    : random_(splitMix64(params.seed ^ splitMix64(0x64617274ull + uint64_t(tile) * 2 + uint64_t(kind)))),
      tileSize_(params.tileSize), yawLo_(kind == DartKind::Clump ? -params.clumpYawJitter : 0.0f),
      yawHi_(kind == DartKind::Clump ? params.clumpYawJitter : glm::two_pi<float>()),
      mirror_(kind == DartKind::Rock || params.mirrorClumps), volumeCount_(volumeCount) {}

TilePlacement DartStream::next() {
    TilePlacement dart;
    dart.position.x = random_.uniform(0.0f, tileSize_);
    dart.position.y = random_.uniform(0.0f, tileSize_);
    dart.index = uint32_t(random_.next() % volumeCount_);
    dart.yaw = random_.uniform(yawLo_, yawHi_);
    const bool coin = (random_.next() >> 63) != 0; // drawn either way, so the stream stays aligned
    dart.mirrored = mirror_ && coin;
    return dart;
}

std::vector<glm::ivec2> neighbourOffsets(uint32_t t, uint32_t u) {
    const WangTile tile = wangTileFromIndex(t), other = wangTileFromIndex(u);
    std::vector<glm::ivec2> offsets;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dz == 0) {
                if (t == u)
                    offsets.push_back({0, 0});
            } else if (canNeighbour(tile, other, dx, dz)) {
                offsets.push_back({dx, dz});
            }
        }
    return offsets;
}

void checkTileFillParams(const TileFillParams& params, float maxRadius, float cellSize, const std::string& what) {
    char text[320];
    if (!std::isfinite(params.tileSize) || !(params.tileSize > 0.0f))
        throw Error(what + ": tile size " + std::to_string(params.tileSize) + " m is not a positive finite number");
    const float needed = 2.0f * maxRadius + 4.0f * cellSize;
    if (params.tileSize < needed) {
        std::snprintf(text, sizeof text,
                      "%s: tile size %.3f m is smaller than a clump: it must be at least 2 x %.3f m (the largest "
                      "swept footprint radius) + 4 x %.3f m (cells) = %.3f m",
                      what.c_str(), double(params.tileSize), double(maxRadius), double(cellSize), double(needed));
        throw Error(text);
    }
    horizontalMap(0.0f, true, params.windDirection); // throws for a zero or non-finite direction
    if (!std::isfinite(params.clumpYawJitter) || params.clumpYawJitter < 0.0f ||
        params.clumpYawJitter > glm::pi<float>())
        throw Error(what + ": clump yaw jitter " + std::to_string(params.clumpYawJitter) + " rad is outside [0, pi]");
    if (params.maxDarts == 0 || params.maxConsecutiveFailures == 0)
        throw Error(what + ": the dart budget (maxDarts " + std::to_string(params.maxDarts) +
                    ", maxConsecutiveFailures " + std::to_string(params.maxConsecutiveFailures) + ") is zero");
}

// ---- WangTileFill --------------------------------------------------------------------------------

std::vector<uint32_t> WangTileFill::clumpsPerTile() const {
    std::vector<uint32_t> counts;
    for (const TileContent& tile : tiles)
        counts.push_back(uint32_t(tile.clumps.size()));
    return counts;
}

std::vector<uint32_t> WangTileFill::rocksPerTile() const {
    std::vector<uint32_t> counts;
    for (const TileContent& tile : tiles)
        counts.push_back(uint32_t(tile.rocks.size()));
    return counts;
}

double WangTileFill::clumpDensity() const {
    size_t clumps = 0;
    for (const TileContent& tile : tiles)
        clumps += tile.clumps.size();
    return double(clumps) / (double(tiles.size()) * double(tileSize) * double(tileSize));
}

namespace {

void checkVolumes(std::span<const SweptVolume> volumes, const char* kind, float cellSize) {
    for (size_t i = 0; i < volumes.size(); ++i) {
        if (volumes[i].empty())
            throw Error(std::string("tile fill: ") + kind + " volume " + std::to_string(i) + " is empty");
        if (volumes[i].cellSize() != cellSize)
            throw Error(std::string("tile fill: ") + kind + " volume " + std::to_string(i) + " has cell size " +
                        std::to_string(volumes[i].cellSize()) + " m, the first clump's is " + std::to_string(cellSize) +
                        " m");
    }
}

struct Kind {
    DartKind dart;
    std::span<const SweptVolume> volumes;
    std::vector<TilePlacement> TileContent::*list;
};

} // namespace

WangTileFill fillWangTiles(std::span<const SweptVolume> clumps, std::span<const SweptVolume> rocks,
                           const TileFillParams& params) {
    if (clumps.empty())
        throw Error("tile fill: the clump list is empty");
    const float h = clumps[0].cellSize();
    checkVolumes(clumps, "clump", h);
    checkVolumes(rocks, "rock", h);
    float maxRadius = 0.0f;
    int32_t minCellY = std::numeric_limits<int32_t>::max(), maxCellY = std::numeric_limits<int32_t>::min();
    for (std::span<const SweptVolume> volumes : {clumps, rocks})
        for (const SweptVolume& volume : volumes) {
            maxRadius = std::max(maxRadius, volume.footprintRadius());
            minCellY = std::min(minCellY, volume.minCell().y);
            maxCellY = std::max(maxCellY, volume.maxCell().y);
        }
    checkTileFillParams(params, maxRadius, h, "tile fill");

    WangTileFill fill;
    fill.tileSize = params.tileSize;
    fill.windDirection = params.windDirection;
    const float T = params.tileSize;
    // Every cell a dart can reach: the tile grown by the largest radius, plus slack for the grid's
    // widening of turned columns.
    const float lo = -maxRadius - 2.0f * h, hi = T + maxRadius + 2.0f * h;
    OccupancyGrid grid(h, glm::vec2(lo), glm::vec2(hi), minCellY, maxCellY, params.windDirection);
    auto insertAt = [&](const SweptVolume& volume, const TilePlacement& placement, glm::vec2 offset) {
        if (discReaches(placement.position + offset, volume.footprintRadius(), lo, hi))
            grid.insert(volume, placement.transform(offset));
    };

    const Kind kinds[] = {{DartKind::Clump, clumps, &TileContent::clumps},
                          {DartKind::Rock, rocks, &TileContent::rocks}};
    for (const Kind& kind : kinds) {
        if (kind.volumes.empty())
            continue;
        for (uint32_t t = 0; t < kCompleteWangTileCount; ++t) {
            // Everything already placed that can stand next to (or on) this tile.
            grid.clear();
            for (uint32_t u = 0; u < kCompleteWangTileCount; ++u)
                for (glm::ivec2 offset : neighbourOffsets(t, u)) {
                    const glm::vec2 shift = glm::vec2(offset) * T;
                    for (const TilePlacement& placement : fill.tiles[u].clumps)
                        insertAt(clumps[placement.index], placement, shift);
                    for (const TilePlacement& placement : fill.tiles[u].rocks)
                        insertAt(rocks[placement.index], placement, shift);
                }
            // Where this tile's own new instances also appear: it neighbours itself there.
            std::vector<glm::ivec2> selfOffsets = neighbourOffsets(t, t);
            std::erase(selfOffsets, glm::ivec2(0, 0));

            std::vector<TilePlacement>& placed = fill.tiles[t].*kind.list;
            DartStream darts(params, t, kind.dart, uint32_t(kind.volumes.size()));
            uint32_t thrown = 0, failures = 0;
            while (!budgetSpent(params, thrown, failures) &&
                   (kind.dart != DartKind::Rock || placed.size() < params.maxRocksPerTile)) {
                const TilePlacement dart = darts.next();
                ++thrown;
                const SweptVolume& volume = kind.volumes[dart.index];
                if (grid.overlaps(volume, dart.transform())) {
                    ++failures;
                    continue;
                }
                failures = 0;
                placed.push_back(dart);
                grid.insert(volume, dart.transform());
                for (glm::ivec2 offset : selfOffsets)
                    insertAt(volume, dart, glm::vec2(offset) * T);
            }
            (kind.dart == DartKind::Clump ? fill.clumpDarts : fill.rockDarts) += thrown;
        }
    }
    return fill;
}

uint32_t countTileOverlapViolations(const WangTileFill& fill, std::span<const SweptVolume> clumps,
                                    std::span<const SweptVolume> rocks) {
    struct Item {
        const SweptVolume* volume;
        TilePlacement placement;
    };
    std::array<std::vector<Item>, kCompleteWangTileCount> items;
    for (uint32_t t = 0; t < kCompleteWangTileCount; ++t) {
        for (const TilePlacement& p : fill.tiles[t].clumps) {
            if (p.index >= clumps.size())
                throw Error("tile overlap check: clump index " + std::to_string(p.index) + " out of range");
            items[t].push_back({&clumps[p.index], p});
        }
        for (const TilePlacement& p : fill.tiles[t].rocks) {
            if (p.index >= rocks.size())
                throw Error("tile overlap check: rock index " + std::to_string(p.index) + " out of range");
            items[t].push_back({&rocks[p.index], p});
        }
    }
    std::array<uint32_t, kCompleteWangTileCount> violations{};
    tbb::parallel_for(uint32_t(0), kCompleteWangTileCount, [&](uint32_t t) {
        for (uint32_t u = t; u < kCompleteWangTileCount; ++u)
            for (glm::ivec2 offset : neighbourOffsets(t, u)) {
                // Each unordered pair once: (t, u, o) and (u, t, -o) are the same contacts.
                if (u == t && (offset.y < 0 || (offset.y == 0 && offset.x < 0)))
                    continue;
                const glm::vec2 shift = glm::vec2(offset) * fill.tileSize;
                for (size_t i = 0; i < items[t].size(); ++i)
                    for (size_t j = (u == t && offset == glm::ivec2(0)) ? i + 1 : 0; j < items[u].size(); ++j) {
                        const Item& a = items[t][i];
                        const Item& b = items[u][j];
                        if (sweptVolumesOverlap(*a.volume, a.placement.transform(), *b.volume,
                                                b.placement.transform(shift), fill.windDirection))
                            ++violations[t];
                    }
            }
    });
    uint32_t total = 0;
    for (uint32_t v : violations)
        total += v;
    return total;
}

} // namespace meadow
