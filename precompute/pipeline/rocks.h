// The field's rocks as the library keeps them (library/field.h): each rock mesh (plants/rock.h)
// baked once, with the ground around it (static light: no motion, no gradient), and simplified
// into five levels of detail.
#pragma once

#include "library/field.h"
#include "transfer/transfer.h"

#include <array>
#include <vector>

namespace meadow {

// meshoptimizer's edge-collapse simplifier at the plants' triangle fractions (scene
// lod.triangleFractions' defaults), the rim on the ground locked so it stays closed against the
// terrain, stopping at 5 % of the rock's size so a far rock keeps its bulk; each LOD ordered for
// the vertex cache. Deterministic.
std::array<RockLod, kLodCount> buildRockLods(const RockMesh& mesh);

// Bakes (`bake` with a ground grid twice the rock's size) and simplifies every rock.
std::vector<LibraryRock> buildRocks(const std::vector<RockMesh>& meshes, const transfer::BakeSettings& bake);

} // namespace meadow
