// The wind around one plant clump: an incompressible 3D grid fluid solver after Stam 1999,
// "Stable Fluids" (semi-Lagrangian advection, then pressure projection), with inflow at a wind
// level's mean speed plus injected turbulence and gusts (inflow.h), and two-way coupling: plants
// push back on the air through addForce() (docs/ARCHITECTURE.md, Wind and rods).
//
// Units are SI: metres, seconds, m/s, kg/m^3, newtons; y is up and the ground is the plane
// y = grid.origin.y. Air density is kAirDensity.
//
// Discretisation
//   Grid        staggered MAC grid (Harlow & Welch 1965): velocity components live on the faces
//               of their axis, pressure at cell centres, so the projection is exactly
//               divergence-free in the discrete sense and has no checkerboard modes.
//   Advection   semi-Lagrangian (Stam 1999, section 3.2) with an RK2 (midpoint) backtrace; the
//               path uses the cell-centred average velocity, the advected component is sampled
//               trilinearly on its own face grid. A backtrace that leaves the box through a side
//               face samples the ambient wind there, so turbulence and gusts flow in.
//   Projection  multigrid V-cycles with red-black Gauss-Seidel (pressure.h), warm-started from the
//               previous step, until max |div u| * cellSize <= 7e-4 * max(meanSpeed, 0.1 m/s) or
//               12 cycles (measured: 2.0 cycles per step at 0.5 m/s, 3.3 at 9 m/s, dt = 1/30 s).
//               The bound is exact: a cell's divergence after the update is its residual / h^2.
//   Boundaries  upwind side faces (those the wind direction points into the box through):
//               normal velocity prescribed from the ambient wind (pressure Neumann). All other
//               side faces are open: pressure 0 beyond them, velocity extrapolated by advection
//               (outflow, and free lateral exchange for faces parallel to the wind). Ground: no
//               penetration plus a log-law wall function (Launder & Spalding 1974): the first
//               cell layer feels the stress rho * C_d |u| u with C_d = (kappa / ln(z1 / z0))^2,
//               kappa = 0.41, z1 = cellSize / 2, roughness z0 = 1 cm, integrated implicitly. Top:
//               free slip (no flow through, no stress).
//
// Determinism: every parallel loop writes only its own cells and all sums run in a fixed order,
// so the same inputs give bit-identical fields for any number of TBB threads. Memory is allocated
// in the constructor only.
#pragma once

#include "inflow.h"
#include "pressure.h"
#include "wind_params.h"

#include <array>
#include <vector>

namespace meadow {

inline constexpr float kAirDensity = 1.2f; // kg/m^3, dry air near 20 C at sea level

class WindSolver {
  public:
    // Throws meadow::Error for a grid or level that cannot be simulated (non-positive sizes,
    // negative speeds, a direction without a horizontal part, non-finite values). The field starts
    // as the ambient wind at t = 0, projected to be divergence-free.
    WindSolver(const FluidGrid& grid, const WindLevelParams& level);

    // One step of dt seconds (1/60 to 1/30 s is the intended range; larger steps stay stable but
    // smear eddies). Applies the forces accumulated by addForce() and clears them.
    void step(float dt);

    // Trilinear velocity (m/s) at p. Outside the box: the ambient wind, inflowVelocity(p).
    glm::vec3 velocityAt(glm::vec3 p) const;
    // The ambient wind (profile x gusts x turbulence) at p and the current time, m/s.
    glm::vec3 inflowVelocity(glm::vec3 p) const;
    // The mean inflow profile at a height above the ground, m/s (no gusts, no turbulence).
    float inflowProfile(float height) const;

    // Two-way coupling: a body exerting force `force` (N) on the air at p, e.g. minus the drag the
    // air exerts on a rod segment. Accumulated until the next step() and applied as a body force
    // spread over the nearby faces with trilinear weights (total momentum force * dt). Points
    // outside the box are ignored: that air is not simulated.
    void addForce(glm::vec3 p, glm::vec3 force);

    double maxDivergence() const { return maxDivergence_; } // max |div u| over cells, 1/s
    double kineticEnergy() const;                           // 0.5 rho sum |u|^2 dV, J
    float time() const { return static_cast<float>(time_); }
    const FluidGrid& grid() const { return grid_; }
    const WindLevelParams& level() const { return level_; }
    int lastPressureCycles() const { return lastPressureCycles_; }

  private:
    struct FaceGrid {
        glm::ivec3 dims;
        glm::vec3 offset; // position of sample (0,0,0) in cell units
        std::vector<float> values;
        size_t index(int i, int j, int k) const {
            return static_cast<size_t>(i) +
                   static_cast<size_t>(dims.x) * (static_cast<size_t>(j) + static_cast<size_t>(dims.y) * k);
        }
    };

    bool outsideSides(glm::vec3 cellCoord) const;
    glm::vec3 samplePathVelocity(glm::vec3 cellCoord) const;
    float sampleComponent(const FaceGrid& face, int axis, glm::vec3 cellCoord) const;
    void applyForces(float dt);
    void updateCellVelocity();
    template <int Axis> void advectAxis(float dt);
    void advect(float dt);
    void applyGroundStress(float dt);
    void applyBoundaries();
    void project();

    FluidGrid grid_;
    WindLevelParams level_;
    InflowField inflow_;
    glm::ivec3 n_;
    float h_;
    std::array<bool, 6> inflowFace_{}; // -x, +x, -y, +y, -z, +z
    FaceGrid velocity_[3];
    FaceGrid advected_[3];
    FaceGrid force_[3];
    bool hasForce_ = false;
    std::vector<glm::vec4> cellVelocity_; // cell-centred averages (w unused), for backtrace paths
    PressureSolver pressure_;
    double time_ = 0.0;
    double maxDivergence_ = 0.0;
    int lastPressureCycles_ = 0;
};

} // namespace meadow
