// A library turned into what the field renderer draws: its clumps and rocks (FieldClump), their
// instances, and the scenery (terrain, wind direction, LOD choice, sky).
#pragma once

#include "library/library.h"
#include "render/field_renderer.h"

#include <vector>

namespace meadow {

// The default screen-space error of the levels of detail (--lod-tolerance): each LOD's RMS distance
// from the full mesh over simulated frames, in pixels, where it takes over.
inline constexpr float kDefaultLodTolerancePixels = 0.3f;

// The far field's projected radius when none is given (--far-radius), in pixels at the default
// tolerance: below it a clump is drawn as surface-sample splats. In the full preset's library at
// 0.3 px it lies just below the radius where LOD 3 would take over (33 px), within that switch's
// crossfade band, so LOD 2 hands over to the far field, which replaces LODs 3 and 4, the meshes
// that keep the least of LOD 0's area (in the ci preset's coarser LODs it replaces LODs 2 to 4);
// measured as the radius whose picture is nearest LOD 0 at 1280x720 (docs/BENCHMARKS.md). It
// scales with the tolerance as the switch radii do, so it keeps its place among them.
inline constexpr float kDefaultFarRadiusPixels = 28.0f;
inline float defaultFarRadius(float lodTolerancePixels) {
    return kDefaultFarRadiusPixels * lodTolerancePixels / kDefaultLodTolerancePixels;
}

// The spacing of the terrain mesh's grid, in m: a fifth of the finest octave's wavelength, at least
// 0.5 and at most 2 (2 m in the bundled field). The mesh then lies within about 2 % of the amplitude
// of the height the clumps stand on (2 cm there; 5 mm at 1 m). A 1 m grid drew four times the
// triangles, 42,000, and lavapipe's draw pass took about 9 ms more for them, most of them slivers a
// pixel high at the far side of the field (docs/BENCHMARKS.md, "The terrain at 2 m").
float terrainMeshSpacing(const TerrainParams& terrain);

// The library's terrain, wind direction, LOD choice and sky, as the field renderer draws them. The
// switch radii put each LOD's error (RMS distance over simulated frames) at `lodTolerancePixels`
// (> 0) for the clump whose error is largest for its size: they scale with it.
FieldScenery fieldScenery(const Library& library, float lodTolerancePixels = kDefaultLodTolerancePixels);

// The library's clumps (mean pose, LODs, motion, light transfer), then its rocks (static, with
// their LODs), as the field renderer draws them. Deterministic.
std::vector<FieldClump> fieldClumps(const Library& library);

// The field's clump instances, then its rocks (their `mesh` after the clumps, as fieldClumps).
std::vector<gpu::GpuInstance> fieldInstances(const Library& library);

} // namespace meadow
