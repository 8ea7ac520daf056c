#include "placement/wang_tiles.h"

#include "core/error.h"
#include "core/random.h"

#include <string>

namespace meadow {
namespace {

void checkSize(uint32_t width, uint32_t height, const char* what) {
    if (width == 0 || height == 0)
        throw Error(std::string(what) + ": a tiling of " + std::to_string(width) + " x " + std::to_string(height) +
                    " tiles is empty");
}

// One bit from SplitMix64 over the edge's coordinates and axis (0: a north edge, 1: a west edge).
uint8_t edgeColour(int64_t x, int64_t y, uint64_t axis, uint64_t seed) {
    uint64_t h = splitMix64(seed ^ 0x57616e6754696c65ull); // "WangTile"
    h = splitMix64(h ^ uint64_t(x));
    h = splitMix64(h ^ uint64_t(y));
    h = splitMix64(h ^ axis);
    return uint8_t(h >> 63);
}

} // namespace

std::array<uint32_t, kCohenWangTileCount> cohenWangTiles() {
    std::array<uint32_t, kCohenWangTileCount> tiles{};
    uint32_t i = 0;
    for (uint8_t n = 0; n < 2; ++n)
        for (uint8_t w = 0; w < 2; ++w) {
            tiles[i++] = wangTileIndex({n, n, w, w});                           // (s, e) = (w, n)
            tiles[i++] = wangTileIndex({n, uint8_t(1 - n), uint8_t(1 - w), w}); // the complement
        }
    return tiles;
}

bool canNeighbour(const WangTile& t, const WangTile& u, int dx, int dz) {
    if (dx != 0 && dz != 0)
        return true; // across a corner
    if (dx == 1)
        return u.w == t.e;
    if (dx == -1)
        return u.e == t.w;
    if (dz == 1)
        return u.n == t.s;
    if (dz == -1)
        return u.s == t.n;
    return false; // (0, 0) is the tile itself, not a neighbour
}

WangTiling scanlineWangTiling(uint32_t width, uint32_t height, uint64_t seed) {
    checkSize(width, height, "scan-line Wang tiling");
    const std::array<uint32_t, kCohenWangTileCount> set = cohenWangTiles();
    WangTiling tiling{width, height, std::vector<uint32_t>(size_t(width) * height)};
    Random random(seed);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            std::array<uint32_t, kCohenWangTileCount> candidates{};
            uint32_t count = 0;
            for (uint32_t index : set) {
                const WangTile tile = wangTileFromIndex(index);
                if (y > 0 && tile.n != wangTileFromIndex(tiling.at(x, y - 1)).s)
                    continue;
                if (x > 0 && tile.w != wangTileFromIndex(tiling.at(x - 1, y)).e)
                    continue;
                candidates[count++] = index;
            }
            // Never empty: the set has two tiles for every (n, w).
            tiling.tiles[size_t(y) * width + x] = candidates[random.next() % count];
        }
    return tiling;
}

uint32_t hashWangTileAt(int64_t x, int64_t y, uint64_t seed) {
    return wangTileIndex({edgeColour(x, y, 0, seed), edgeColour(x + 1, y, 1, seed), edgeColour(x, y + 1, 0, seed),
                          edgeColour(x, y, 1, seed)});
}

WangTiling hashWangTiling(int64_t x0, int64_t y0, uint32_t width, uint32_t height, uint64_t seed) {
    checkSize(width, height, "hash Wang tiling");
    WangTiling tiling{width, height, std::vector<uint32_t>(size_t(width) * height)};
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            tiling.tiles[size_t(y) * width + x] = hashWangTileAt(x0 + int64_t(x), y0 + int64_t(y), seed);
    return tiling;
}

uint32_t countEdgeMismatches(const WangTiling& tiling) {
    uint32_t mismatches = 0;
    for (uint32_t y = 0; y < tiling.height; ++y)
        for (uint32_t x = 0; x < tiling.width; ++x) {
            const WangTile tile = wangTileFromIndex(tiling.at(x, y));
            if (x + 1 < tiling.width && wangTileFromIndex(tiling.at(x + 1, y)).w != tile.e)
                ++mismatches;
            if (y + 1 < tiling.height && wangTileFromIndex(tiling.at(x, y + 1)).n != tile.s)
                ++mismatches;
        }
    return mismatches;
}

} // namespace meadow
