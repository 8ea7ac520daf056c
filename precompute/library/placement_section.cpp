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
    r.expectEnd();
    try {
        Terrain check(t); // validates the parameters
    } catch (const Error& e) {
        throw Error(where + ": " + e.what());
    }
    if (s.clumpsPerTile.size() != s.tiles || s.rocksPerTile.size() != s.tiles || !(s.tileSize > 0.0f) ||
        !std::isfinite(s.tileSize) || !std::isfinite(s.densityVsPoissonDisc) ||
        !(std::abs(glm::length(field.windDirection) - 1.0f) < 1e-3f))
        throw Error(where + ": inconsistent tile figures");
}

} // namespace meadow
