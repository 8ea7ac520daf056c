// The Poisson-disc baseline of Cohen et al. 2003 (tile_fill.h): discs of each clump's swept
// radius, the same darts and neighbour rules as the voxel fill, so densityVsPoissonDisc measures
// only what the voxel test gains (Cove & James 2004, section 2.2).
#include "core/error.h"
#include "placement/dart_throwing.h"
#include "placement/tile_fill.h"

#include <algorithm>
#include <cmath>

namespace meadow {

std::vector<uint32_t> PoissonDiscFill::clumpsPerTile() const {
    std::vector<uint32_t> counts;
    for (const std::vector<TilePlacement>& tile : tiles)
        counts.push_back(uint32_t(tile.size()));
    return counts;
}

double PoissonDiscFill::clumpDensity() const {
    size_t clumps = 0;
    for (const std::vector<TilePlacement>& tile : tiles)
        clumps += tile.size();
    return double(clumps) / (double(tiles.size()) * double(tileSize) * double(tileSize));
}

PoissonDiscFill fillWangTilesPoissonDisc(std::span<const float> radii, const TileFillParams& params) {
    if (radii.empty())
        throw Error("Poisson-disc fill: the clump list is empty");
    float maxRadius = 0.0f;
    for (size_t i = 0; i < radii.size(); ++i) {
        if (!std::isfinite(radii[i]) || !(radii[i] > 0.0f))
            throw Error("Poisson-disc fill: clump " + std::to_string(i) + " radius " + std::to_string(radii[i]) +
                        " m is not a positive finite number");
        maxRadius = std::max(maxRadius, radii[i]);
    }
    checkTileFillParams(params, maxRadius, 0.0f, "Poisson-disc fill");

    PoissonDiscFill fill;
    fill.tileSize = params.tileSize;
    const float T = params.tileSize;
    struct Disc {
        glm::vec2 centre;
        float radius;
    };
    for (uint32_t t = 0; t < kCompleteWangTileCount; ++t) {
        // Discs already placed that can reach a dart of this tile (it reaches at most maxRadius out).
        std::vector<Disc> discs;
        auto addDisc = [&](glm::vec2 centre, float radius) {
            if (discReaches(centre, radius + maxRadius, 0.0f, T))
                discs.push_back({centre, radius});
        };
        for (uint32_t u = 0; u < kCompleteWangTileCount; ++u)
            for (glm::ivec2 offset : neighbourOffsets(t, u))
                for (const TilePlacement& placed : fill.tiles[u])
                    addDisc(placed.position + glm::vec2(offset) * T, radii[placed.index]);
        std::vector<glm::ivec2> selfOffsets = neighbourOffsets(t, t);
        std::erase(selfOffsets, glm::ivec2(0, 0));

        DartStream darts(params, t, DartKind::Clump, uint32_t(radii.size()));
        uint32_t thrown = 0, failures = 0;
        while (!budgetSpent(params, thrown, failures)) {
            const TilePlacement dart = darts.next();
            ++thrown;
            const float radius = radii[dart.index];
            const bool hit = std::any_of(discs.begin(), discs.end(), [&](const Disc& disc) {
                const glm::vec2 d = disc.centre - dart.position;
                const float reach = disc.radius + radius;
                return glm::dot(d, d) < reach * reach; // touching discs do not overlap
            });
            if (hit) {
                ++failures;
                continue;
            }
            failures = 0;
            fill.tiles[t].push_back(dart);
            addDisc(dart.position, radius);
            for (glm::ivec2 offset : selfOffsets)
                addDisc(dart.position + glm::vec2(offset) * T, radius);
        }
        fill.darts += thrown;
    }
    return fill;
}

PoissonDiscFill fillWangTilesPoissonDisc(std::span<const SweptVolume> clumps, const TileFillParams& params) {
    std::vector<float> radii;
    for (const SweptVolume& volume : clumps)
        radii.push_back(volume.footprintRadius());
    return fillWangTilesPoissonDisc(radii, params);
}

double densityVsPoissonDisc(const WangTileFill& voxels, const PoissonDiscFill& discs) {
    const double disc = discs.clumpDensity();
    if (!(disc > 0.0))
        throw Error("density comparison: the Poisson-disc fill placed no clump");
    return voxels.clumpDensity() / disc;
}

} // namespace meadow
