// Procedural rocks (docs/ARCHITECTURE.md, Plants): static, lit by PRT like the plants, placed in
// the Wang tiles by the same dart throwing as the clumps (precompute/placement) — Cove & James 2004
// scatter "thousands of rock instances" through their field that way.
//
// Each rock is a subdivided icosphere displaced along its radius by two octaves of smooth 3D
// value noise, stretched along a random horizontal axis, squashed vertically, and half-buried:
// lowered so that a quarter to nearly half of its height is below ground, then cut at y = 0 with
// the buried part removed. What remains is "watertight above ground": every edge is shared by
// exactly two triangles, wound consistently, except the cut edges, which lie on y = 0 and form
// closed loops that the ground closes. Normals are the displaced surface's (area-weighted over the
// uncut sphere, so the cut does not bend them), unit and outward. UVs are a top-down planar
// projection, u = x / size + 1/2, v = z / size + 1/2, continuous (no seam) for a tiling rock
// texture.
//
// Units and frame: metres, y up, the rock's footprint centred near the origin on y = 0. Rock i
// depends only on the seed and i; the same inputs give identical bytes.
#pragma once

#include "library/field.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace meadow {

struct RockParams {
    uint32_t subdivisions = 3; // icosphere subdivisions, 1 .. 6 (20 * 4^s triangles before the cut)
    float minSize = 0.2f;      // m: the range of a rock's size, its larger horizontal extent above ground
    float maxSize = 0.6f;
};

// "ci" (2 subdivisions) or "full" (3). Throws meadow::Error for other names.
RockParams rockParamsForPreset(const std::string& preset);

// `count` rock variants. Throws meadow::Error for subdivisions outside 1 .. 6 or sizes that are
// not finite with 0 < minSize <= maxSize.
std::vector<RockMesh> makeRocks(uint64_t seed, uint32_t count, const RockParams& params);

} // namespace meadow
