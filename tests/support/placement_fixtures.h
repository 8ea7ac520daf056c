// Shared inputs of the placement tests: realistic swept volumes (procedural iris clumps leaning in
// a synthetic wind, half-buried rocks) and the tile fill made from them. The lead feeds the true
// simulated frames later; a rest mesh turned downwind by up to 20 degrees at the top, with a
// little backswing and crosswind sway, gives swept volumes of the same character (wider downwind,
// narrow at the rhizomes).
#pragma once

#include "placement/swept_volume.h"
#include "placement/tile_fill.h"
#include "plants/plant.h"

#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace meadow::test {

inline constexpr uint64_t kPlantSeed = 20040807;
inline constexpr float kCellSize = 0.025f; // m
inline constexpr float kMargin = 0.025f;   // m: one cell of safety
inline const glm::vec2 kWind{1.0f, 0.0f};  // (x, z)

// Frames of the rest mesh bent about its base: each vertex turned about the horizontal axis
// across the wind by maxAngle * lean * (y / height), leans -0.2 .. 1, then about the wind axis by
// a crosswind sway of up to 0.15 of that. 15 frames.
std::vector<std::vector<glm::vec3>> leanFrames(const PlantMesh& mesh, glm::vec2 wind, float maxAngle);

// Four "ci" iris clumps, swept by leanFrames(0.35 rad) and voxelized at kCellSize, kMargin.
const std::vector<SweptVolume>& irisVolumes();
// Four "ci" rocks, voxelized solid (fillEnclosed) at kCellSize, kMargin.
const std::vector<SweptVolume>& rockVolumes();
// The default fill of the complete tile set from irisVolumes and rockVolumes (seed 7).
TileFillParams defaultFillParams();
const WangTileFill& defaultFill();

// Runs `call` and expects a meadow::Error whose message contains `fragment`.
void expectError(const std::function<void()>& call, const std::string& fragment);

} // namespace meadow::test
