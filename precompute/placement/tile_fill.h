// Filling Wang tiles with clumps and rocks by dart throwing (Cohen et al. 2003, section 4), with
// the extension of Cove & James 2004, section 2.2: a dart is tested against swept volumes (voxel
// sets, swept_volume.h) instead of discs of the swept radius, so clumps pack far denser. A
// Poisson-disc fill with the same darts and the same neighbour rules is the baseline the gain is
// measured against.
//
// Rule: a dart in tile t is accepted only if its volume overlaps none of t's own instances, nor
// the instances of every tile of the complete set that can sit next to t — across each edge every
// tile whose facing edge has t's colour (t itself included), across each corner every tile — each
// at its offset of one tile size. The tiles are filled one after another, every dart tested
// against what is already placed, so no tiling from the complete set (wang_tiles.h), and hence
// none from Cohen's 8, can ever put two volumes in contact. That needs no instance to reach past
// the tiles next to its own: the tile size must be at least 2 R + 4 h for the largest footprint
// radius R and cell size h (clumps two tiles apart are then more than 2 R apart).
//
// Tile frame: a tile is the square [0, T) x [0, T) of (x, z), its north-west corner at the
// origin (north is -z, east +x, as in wang_tiles.h); every instance stands at y = 0 on the tile.
// Deterministic for the seed (the fill is sequential; the darts of each tile and kind come from
// their own Random stream).
#pragma once

#include "placement/instance.h"
#include "placement/swept_volume.h"
#include "placement/wang_tiles.h"

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace meadow {

struct TileFillParams {
    float tileSize = 6.0f;                  // T (m), the edge of a square tile (~38 leaning iris clumps)
    glm::vec2 windDirection{1.0f, 0.0f};    // (x, z); mirrored instances reflect about the plane holding it
    float clumpYawJitter = 0.3f;            // clump yaw uniform in [-j, j] (rad); rocks take any yaw
    bool mirrorClumps = true;               // each clump dart mirrored with probability 1/2 (rocks always may be)
    uint32_t maxConsecutiveFailures = 1000; // per tile and kind: stop after this many rejections in a row
    uint32_t maxDarts = 40000;              // per tile and kind: stop after this many darts
    uint32_t maxRocksPerTile = 10;          // rocks stop here even while darts still land
    uint64_t seed = 0;
};

// An instance on a tile: (x, z) in the tile frame, the rest as InstanceTransform (y = 0).
struct TilePlacement {
    glm::vec2 position{0.0f};
    float yaw = 0.0f;
    bool mirrored = false;
    uint32_t index = 0; // which clump (or rock) volume

    InstanceTransform transform(glm::vec2 offset = glm::vec2(0.0f)) const {
        return {glm::vec3(position.x + offset.x, 0.0f, position.y + offset.y), yaw, mirrored};
    }
};

struct TileContent {
    std::vector<TilePlacement> clumps; // in the order they were accepted
    std::vector<TilePlacement> rocks;
};

// The complete set, filled. tiles[i] is the tile wangTileFromIndex(i).
struct WangTileFill {
    float tileSize = 0.0f;
    glm::vec2 windDirection{1.0f, 0.0f};
    std::array<TileContent, kCompleteWangTileCount> tiles;
    uint64_t clumpDarts = 0; // thrown, all tiles
    uint64_t rockDarts = 0;

    std::vector<uint32_t> clumpsPerTile() const;
    std::vector<uint32_t> rocksPerTile() const;
    // Clumps per square metre over the whole set.
    double clumpDensity() const;
};

// Throws meadow::Error when there is no clump volume, volumes differ in cell size or are empty,
// the tile size is not finite or is smaller than 2 R + 4 h (naming both), the wind direction is
// zero or not finite, the yaw jitter is negative or not finite, or a dart budget is zero. Rocks
// may be empty (then no rock is placed). Clumps are placed in every tile first, then rocks.
WangTileFill fillWangTiles(std::span<const SweptVolume> clumps, std::span<const SweptVolume> rocks,
                           const TileFillParams& params);

// Every pair of placed volumes (own tile, and every neighbour of the complete set across edges
// and corners at its offset) that sweptVolumesOverlap reports: 0 for a fill from fillWangTiles.
// An independent check: exact box tests over all tile pairs and offsets, not the fill's grid.
uint32_t countTileOverlapViolations(const WangTileFill& fill, std::span<const SweptVolume> clumps,
                                    std::span<const SweptVolume> rocks);

// The baseline: the same darts (same seeds, same budget), accepted when the dart's disc of its
// clump's radius is disjoint from every placed disc under the same neighbour rules.
struct PoissonDiscFill {
    float tileSize = 0.0f;
    std::array<std::vector<TilePlacement>, kCompleteWangTileCount> tiles;
    uint64_t darts = 0;

    std::vector<uint32_t> clumpsPerTile() const;
    double clumpDensity() const;
};

// radii[i]: clump i's disc radius (its swept footprint radius). Same errors as fillWangTiles.
PoissonDiscFill fillWangTilesPoissonDisc(std::span<const float> radii, const TileFillParams& params);

// The swept volumes' own footprint radii.
PoissonDiscFill fillWangTilesPoissonDisc(std::span<const SweptVolume> clumps, const TileFillParams& params);

// (voxel-test clumps per area) / (disc clumps per area); the design asks >= 1.5.
double densityVsPoissonDisc(const WangTileFill& voxels, const PoissonDiscFill& discs);

} // namespace meadow
