// Procedural bearded-iris clumps, the building blocks of the field (Cove & James 2004, section 2:
// "four clumps of six to seven irises in close contact").
//
// Each iris grows from a rhizome a few centimetres from its neighbours': a flat fan of 5–8
// sword-shaped leaves (0.4–0.9 m, 2–4 cm wide, folded along the midrib, gently arching), a stem
// (0.5–0.9 m) that rises above the leaves, and one or two flowers, each with three drooping
// bearded falls, three upright cupped standards and three style arms. Sizes follow garden
// bearded irises; everything else about a clump comes from the seed.
//
// Output (plant.h): one mesh per clump with UVs into the iris atlas (atlas.h), one Rod per leaf
// and per stem. Leaf vertices bind to their leaf rod by arc length, stem vertices to the stem rod,
// flower vertices rigidly to the stem node they sit on (the top flower to the last node).
// Deterministic: the same seed, clump count and parameters give identical bytes.
#pragma once

#include "plant.h"

#include <cstdint>
#include <string>
#include <vector>

namespace meadow {

// Tessellation only; the shapes themselves do not depend on it, so presets differ in smoothness,
// not in the plants.
struct IrisParams {
    uint32_t leafRows = 9;        // mesh rows along a leaf, the pointed tip excluded (>= 2)
    uint32_t leafColumns = 5;     // vertices across a leaf, odd so one lies on the midrib (>= 3)
    uint32_t leafNodes = 10;      // rod nodes per leaf (3 .. 12)
    uint32_t stemRows = 10;       // rings along a stem (>= 2)
    uint32_t stemSides = 6;       // vertices around a stem (>= 3)
    uint32_t stemNodes = 10;      // rod nodes per stem (3 .. 12)
    uint32_t petalRows = 5;       // rows along a fall or standard (>= 2)
    uint32_t petalColumns = 5;    // vertices across a fall or standard (>= 2)
    uint32_t styleArmRows = 4;    // rows along a style arm (>= 2)
    uint32_t styleArmColumns = 3; // vertices across a style arm (>= 2)
    uint32_t atlasSize = 1024;    // texels per side of the matching atlas (makeIrisAtlas)
};

// "ci" (coarse, about a third of the triangles) or "full". Throws meadow::Error for other names.
IrisParams irisParamsForPreset(const std::string& preset);

// `clumpCount` variants (the paper uses 4), named "iris-clump-0" and so on. Clump i depends only
// on the seed and i, not on clumpCount. Throws meadow::Error if the params are out of range.
std::vector<PlantClump> makeIrisClumps(uint64_t seed, uint32_t clumpCount, const IrisParams& params);

} // namespace meadow
