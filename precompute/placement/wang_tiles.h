// Wang tiles (Cohen, Shade, Hiller & Deussen 2003, "Wang Tiles for Image and Texture
// Generation"): square tiles with a colour on each edge, laid so that shared edges match. Two
// colours per edge axis: north and south edges draw from one pair {0, 1}, east and west from
// another {0, 1}.
//
// The complete set holds all 16 colourings. Cohen et al.'s 8-tile set is a subset with exactly
// two tiles for each (north, west) pair, enough for their stochastic scan-line tiling. A direct,
// hash-based tiling in the manner of Lagae & Dutré ("A procedural object distribution function",
// 2005; "Long period hash functions for procedural texturing", 2006) names the colour of every
// edge from a hash of its integer coordinates, so any tile of an unbounded plane is known without
// its neighbours; it needs all 16 tiles. Tiles are filled (tile_fill.h) so that any tiling from
// the complete set is collision free, which covers both.
//
// Axes: tile (x, y) of a tiling is column x (growing east, world +x) and row y (growing south,
// world +z). A tile's north edge is its -z edge, shared with tile (x, y - 1)'s south edge; its
// west edge is its -x edge, shared with tile (x - 1, y)'s east edge.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace meadow {

struct WangTile {
    uint8_t n = 0, e = 0, s = 0, w = 0; // edge colours, each 0 or 1
};

inline constexpr uint32_t kCompleteWangTileCount = 16;
inline constexpr uint32_t kCohenWangTileCount = 8;

// A tile's index in the complete set: n + 2 e + 4 s + 8 w; and back.
inline uint32_t wangTileIndex(const WangTile& t) {
    return uint32_t(t.n) | uint32_t(t.e) << 1 | uint32_t(t.s) << 2 | uint32_t(t.w) << 3;
}
inline WangTile wangTileFromIndex(uint32_t index) {
    return {uint8_t(index & 1u), uint8_t(index >> 1 & 1u), uint8_t(index >> 2 & 1u), uint8_t(index >> 3 & 1u)};
}

// Cohen et al.'s 8 tiles as indices into the complete set: for each (n, w) the two tiles with
// (s, e) = (w, n) and (1 - w, 1 - n). The two choices for any (n, w) differ in both the south
// and the east colour, so each choice steers both following constraints, and every colour appears
// on every edge of four of the eight tiles.
std::array<uint32_t, kCohenWangTileCount> cohenWangTiles();

// Whether tile `u` may sit at offset (dx, dz) in tiles (each -1, 0 or 1, not both 0) from tile
// `t` in a tiling from the complete set: across an edge the facing colours must agree; across a
// corner any tile can (the two tiles share no edge, and the two between them can always be
// chosen from the complete set).
bool canNeighbour(const WangTile& t, const WangTile& u, int dx, int dz);

// A rectangle of tiles, row-major: tiles[y * width + x] is an index into the complete set.
struct WangTiling {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint32_t> tiles;
    uint32_t at(uint32_t x, uint32_t y) const { return tiles[size_t(y) * width + x]; }
};

// Cohen et al.'s stochastic scan-line tiling: rows from north to south, each from west to east;
// every tile is drawn uniformly among the 8 whose north and west colours match the tiles already
// placed above and to the left (any, along the first row and column). Deterministic for the
// seed. Throws meadow::Error for a zero width or height.
WangTiling scanlineWangTiling(uint32_t width, uint32_t height, uint64_t seed);

// The tile at (x, y) of the unbounded hash tiling: the north edge of (x, y) takes the colour
// hash(seed, x, y, north) and the west edge hash(seed, x, y, west) (SplitMix64 mixing, one bit);
// east and south are the west and north colours of the next tiles. Pure: any (x, y), any order.
uint32_t hashWangTileAt(int64_t x, int64_t y, uint64_t seed);

// The hash tiling's window of width x height tiles starting at (x0, y0). Throws meadow::Error for a
// zero width or height.
WangTiling hashWangTiling(int64_t x0, int64_t y0, uint32_t width, uint32_t height, uint64_t seed);

// Number of shared edges whose two colours differ (0 for a valid tiling).
uint32_t countEdgeMismatches(const WangTiling& tiling);

} // namespace meadow
