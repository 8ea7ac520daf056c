// Inputs of the wind solver: the simulated box and one wind level. Split from fluid.h so that the
// inflow model (inflow.h) and the solver share them without including each other.
//
// Units are SI throughout: metres, seconds, m/s, kg/m^3, newtons. The frame is y up; the ground is
// the horizontal plane y = FluidGrid::origin.y, and heights are measured from it.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

namespace meadow {

// An axis-aligned box of cubic cells. The default (24 x 20 x 24 cells of 8 cm: 1.92 m x 1.6 m x
// 1.92 m) surrounds one iris clump centred on the origin. Cell counts divisible by 4 let the
// multigrid pressure solver coarsen twice or more (see pressure.h); every count must be >= 2.
struct FluidGrid {
    glm::ivec3 cells{24, 20, 24};
    float cellSize = 0.08f;                 // m
    glm::vec3 origin{-0.96f, 0.0f, -0.96f}; // m, the minimum corner; origin.y is the ground
};

// One wind level (four by default, calm to strong, one direction; docs/ARCHITECTURE.md, Wind and
// rods).
struct WindLevelParams {
    glm::vec3 direction{1, 0, 0}; // horizontal unit vector (y is ignored and the rest renormalised)
    float meanSpeed = 2.0f;       // m/s at the reference height of 1 m above the ground
    float turbulence = 0.25f;     // relative intensity of injected fluctuations (std / mean, target)
    float gustPeriod = 4.0f;      // s, time scale of low-frequency gusts
    uint64_t seed = 1;
};

} // namespace meadow
