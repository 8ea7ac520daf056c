#include "library/sections.h"

#include "core/error.h"

#include <cmath>

namespace meadow {

void writePlacementSection(ByteWriter& w, const Library& library) {
    const TerrainParams& terrain = library.field.terrain;
    const glm::vec2 windDirection = library.field.windDirection;
    const PlacementStats& s = library.field.stats;
    w.f32(windDirection.x);
    w.f32(windDirection.y);
    w.f32(terrain.amplitude);
    w.f32(terrain.wavelength);
    w.u32(terrain.octaves);
    w.u64(terrain.seed);
    w.u32(s.tiles);
    w.u32s(s.clumpsPerTile);
    w.u32s(s.rocksPerTile);
    w.f32(float(s.densityVsPoissonDisc));
    w.u32(s.overlapViolations);
    w.u32(s.tilesX);
    w.u32(s.tilesY);
    w.f32(s.tileSize);
    w.u32(s.overlaps3dFound);
    w.u32(s.clumpsRemoved3d);
    w.u32(s.rocksRemoved3d);
    w.u32(s.overlapViolations3d);
    w.f32s(s.sweptFootprintRadius);
    w.string(s.tiling);
    w.u32s(s.fieldTiles);
    w.u32s(s.poissonClumpsPerTile);
    w.u32s(s.sweptFrames);
    w.u32s(s.simulatedFrames);
    w.u32(s.overlapViolationsAllFrames);
    w.u32(s.overlapViolations3dAllFrames);
}

void readPlacementSection(ByteReader& r, const std::string& where, Library& library) {
    LibraryField& field = library.field;
    field.windDirection.x = r.f32();
    field.windDirection.y = r.f32();
    TerrainParams& t = field.terrain;
    t.amplitude = r.f32();
    t.wavelength = r.f32();
    t.octaves = r.u32();
    t.seed = r.u64();
    PlacementStats& s = field.stats;
    s.tiles = r.u32();
    s.clumpsPerTile = r.u32s(1024);
    s.rocksPerTile = r.u32s(1024);
    s.densityVsPoissonDisc = r.f32();
    s.overlapViolations = r.u32();
    s.tilesX = r.u32();
    s.tilesY = r.u32();
    s.tileSize = r.f32();
    s.overlaps3dFound = r.u32();
    s.clumpsRemoved3d = r.u32();
    s.rocksRemoved3d = r.u32();
    s.overlapViolations3d = r.u32();
    s.sweptFootprintRadius = r.f32s(64);
    s.tiling = r.string();
    s.fieldTiles = r.u32s(1024);
    s.poissonClumpsPerTile = r.u32s(1024);
    s.sweptFrames = r.u32s(64);
    s.simulatedFrames = r.u32s(64);
    s.overlapViolationsAllFrames = r.u32();
    s.overlapViolations3dAllFrames = r.u32();
    r.expectEnd();
    try {
        Terrain check(t); // validates the parameters
    } catch (const Error& e) {
        throw Error(where + ": " + e.what());
    }
    if (s.clumpsPerTile.size() != s.tiles || s.rocksPerTile.size() != s.tiles || !(s.tileSize > 0.0f) ||
        !std::isfinite(s.tileSize) || !std::isfinite(s.densityVsPoissonDisc) ||
        !(std::abs(glm::length(field.windDirection) - 1.0f) < 1e-3f) || s.poissonClumpsPerTile.size() != s.tiles ||
        s.fieldTiles.empty() || s.sweptFrames.size() != s.sweptFootprintRadius.size() ||
        s.simulatedFrames.size() != s.sweptFrames.size())
        throw Error(where + ": inconsistent tile figures");
    if (s.tiling != "scanline" && s.tiling != "hash")
        throw Error(where + ": unknown tiling '" + s.tiling.substr(0, 32) + "'");
    for (size_t i = 0; i < s.fieldTiles.size(); ++i)
        if (s.fieldTiles[i] >= s.tiles || (i > 0 && s.fieldTiles[i] <= s.fieldTiles[i - 1]))
            throw Error(where + ": the field's tiles are not ascending indices into the set");
}

} // namespace meadow
