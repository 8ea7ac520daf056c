// Pressure Poisson solver of the wind's projection step (Stam 1999, section 3.2): geometric
// multigrid V-cycles on a cell-centred grid, red-black Gauss-Seidel smoothing (Trottenberg,
// Oosterlee & Schueller, "Multigrid", 2001, chapter 2).
//
// It solves A phi = b with, for each cell c,
//     (A phi)_c = diag_c * phi_c - sum_{neighbours n inside the grid} phi_n,
// where diag_c counts the neighbours inside the grid plus the Dirichlet boundary faces (phi = 0 in
// the ghost cell beyond an open face); Neumann faces (walls, inflow) add nothing. This is the
// standard 7-point Laplacian scaled by -h^2. At least one face must be Dirichlet, so A is
// symmetric positive definite.
//
// Layout: arrays are padded by one ghost cell on every side and are zero there; index with
// index(i, j, k), i in [0, cells.x) etc. Coarse levels halve every dimension while all stay even
// and >= 2; the coarsest is solved by 40 red-black sweeps. The solver owns its memory; solve()
// allocates nothing.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <vector>

namespace meadow {

class PressureSolver {
  public:
    // dirichletFaces: -x, +x, -y, +y, -z, +z; true = open (phi = 0 beyond), false = wall.
    PressureSolver(glm::ivec3 cells, const std::array<bool, 6>& dirichletFaces);

    size_t index(int i, int j, int k) const { return levels_[0].index(i, j, k); }
    std::vector<float>& phi() { return levels_[0].phi; } // kept between solves: a warm start
    std::vector<float>& rhs() { return levels_[0].rhs; }
    glm::ivec3 strides() const { return {1, levels_[0].strideY, levels_[0].strideZ}; }

    // At least one V-cycle (if maxCycles > 0), then more until max |b - A phi| <= tolerance or
    // maxCycles; returns the cycles done.
    int solve(float tolerance, int maxCycles);
    float lastMaxResidual() const { return lastMaxResidual_; }
    int levelCount() const { return static_cast<int>(levels_.size()); }

  private:
    struct Level {
        glm::ivec3 cells;
        int strideY = 0;
        int strideZ = 0;
        std::vector<float> phi, rhs, residual, diag, inverseDiag;
        std::vector<float> slabMax; // per z slab, combined in order
        size_t index(int i, int j, int k) const {
            return static_cast<size_t>(i + 1) + static_cast<size_t>(strideY) * static_cast<size_t>(j + 1) +
                   static_cast<size_t>(strideZ) * static_cast<size_t>(k + 1);
        }
    };

    void smooth(Level& level, int sweeps);
    float computeResidual(Level& level); // returns max |residual|
    void restrictResidual(const Level& fine, Level& coarse);
    void prolongAdd(const Level& coarse, Level& fine);
    void vCycle(size_t levelIndex);

    std::vector<Level> levels_;
    float lastMaxResidual_ = 0.0f;
};

} // namespace meadow
