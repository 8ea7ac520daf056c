// One clump in one wind level: rods driven by the 3D wind solver, two-way coupled, recorded at
// the motion frame rate after the clump has settled into the wind (docs/ARCHITECTURE.md, Wind and
// rods).
#pragma once

#include "plants/plant.h"
#include "sim/rod_system.h"
#include "wind/fluid.h"

#include <cstdint>
#include <vector>

namespace meadow {

struct WindLevelSpec {
    float meanSpeed = 2.0f;   // m/s at 1 m
    float turbulence = 0.25f; // relative intensity of the injected fluctuations
};

struct ClumpSimSettings {
    float frameRate = 30.0f;    // recorded frames per second
    uint32_t substeps = 20;     // rod substeps per frame
    float settleSeconds = 2.0f; // simulated, not recorded: the wind ramps up and the clump settles
    float recordSeconds = 20.0f;
    glm::vec3 windDirection{1.0f, 0.0f, 0.0f};
    float gustPeriod = 4.0f;
    bool twoWayCoupling = true; // the clump's drag acts back on the air
    FluidGrid grid;
    RodMaterial material;
};

struct LevelSimulation {
    uint32_t level = 0;
    uint32_t frames = 0;
    uint32_t nodesPerFrame = 0;
    std::vector<glm::vec3> nodeFrames;    // frames x nodes, rod nodes in RodSystem order
    float maxPenetration = 0.0f;          // deepest contact interpenetration while recording (m)
    double maxKineticEnergy = 0.0;        // J, while recording
    double firstHalfKineticEnergy = 0.0;  // mean J over the first half of the recording
    double secondHalfKineticEnergy = 0.0; // and over the second half (bounded: no growth)
    double maxAirDivergence = 0.0;        // of the wind solver after its projections (1/s)
    uint32_t contactCandidates = 0;       // pairs tested per substep, at the end
};

// Deterministic for the same clump, level, settings and seed.
LevelSimulation simulateClumpLevel(const PlantClump& clump, const WindLevelSpec& wind, uint32_t level,
                                   const ClumpSimSettings& settings, uint64_t seed);

} // namespace meadow
