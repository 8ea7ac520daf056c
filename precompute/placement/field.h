// The field (docs/ARCHITECTURE.md, Placement): a stochastic tiling of the filled Wang tiles
// (tile_fill.h), flattened into plain instance lists on a heightmap terrain (terrain.h), then
// checked in 3D. The run time knows nothing of tiles: it gets the lists.
//
// Beyond Cove & James 2004 (who note that their hills could make neighbours interpenetrate, since
// tiles are filled flat): every pair of instances is tested again where it actually stands, at
// its terrain height, by the exact voxel-box test (instance.h), and each overlap found is resolved
// deterministically by dropping the later instance of the pair, in list order with every clump
// before every rock (so a rock always gives way to a clump). Dropping, not nudging: a nudged
// instance can meet new neighbours, and dropping never can. The final field is checked once more
// from scratch.
//
// World frame: metres, y up. Tile (x, y) of the tiling covers world x in origin.x + [x T, (x+1) T)
// and z in origin.y + [y T, (y+1) T); the field is centred on the world origin. Instances stand
// upright (their axis along +y) at the terrain's height under their origin.
#pragma once

#include "library/terrain.h"
#include "placement/instance.h"
#include "placement/swept_volume.h"
#include "placement/tile_fill.h"
#include "placement/wang_tiles.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <utility>
#include <vector>

namespace meadow {

enum class TilingMethod : uint8_t {
    Scanline, // Cohen et al.'s stochastic scan-line tiling from their 8 tiles (the paper's field)
    Hash,     // the direct hash tiling from all 16 (Lagae & Dutré), the window at tile (0, 0)
};

struct FieldParams {
    uint32_t tilesX = 15; // the paper's 15 x 15
    uint32_t tilesY = 15;
    TilingMethod tiling = TilingMethod::Scanline;
    uint64_t seed = 0;           // the tiling's seed
    bool resolveOverlaps = true; // drop instances that overlap in 3D (false: only count them)
};

// One instance: what the run time needs (the transform of instance.h; y from the terrain).
struct PlacedInstance {
    glm::vec3 position{0.0f};
    float yaw = 0.0f;
    uint32_t index = 0; // clump (or rock) volume / mesh
    bool mirrored = false;

    InstanceTransform transform() const { return {position, yaw, mirrored}; }
};

struct FieldOverlapStats {
    uint64_t candidatePairs = 0; // pairs whose bounding cylinders meet, tested exactly
    uint32_t pairsFound = 0;     // overlapping pairs before resolution
    uint32_t clumpsRemoved = 0;
    uint32_t rocksRemoved = 0;
    uint32_t pairsRemaining = 0; // overlapping pairs in the final field, found by a fresh check
};

struct Field {
    uint32_t tilesX = 0;
    uint32_t tilesY = 0;
    float tileSize = 0.0f;
    glm::vec2 origin{0.0f}; // world (x, z) of tile (0, 0)'s north-west corner
    glm::vec2 windDirection{1.0f, 0.0f};
    WangTiling tiling;
    std::vector<PlacedInstance> clumps; // by tile row, then column, then acceptance order
    std::vector<PlacedInstance> rocks;
    FieldOverlapStats overlaps3d;
};

// Throws meadow::Error for a zero tile count, a fill that does not match the volumes (an index
// out of range, no clump volume), or volumes of differing cell sizes.
Field buildField(const WangTileFill& fill, std::span<const SweptVolume> clumps, std::span<const SweptVolume> rocks,
                 const Terrain& terrain, const FieldParams& params);

// Every pair (i, j), i < j, of the field's instances whose swept volumes overlap where they stand,
// numbered through clumps then rocks (rock r is clumps.size() + r); ascending. A world hash grid
// of buckets two footprint radii wide finds the candidate pairs; the exact test (instance.h)
// decides. Runs on all cores; the same list for any thread count.
std::vector<std::pair<uint32_t, uint32_t>> findFieldOverlaps(const Field& field, std::span<const SweptVolume> clumps,
                                                             std::span<const SweptVolume> rocks,
                                                             uint64_t* candidatePairs = nullptr);

} // namespace meadow
