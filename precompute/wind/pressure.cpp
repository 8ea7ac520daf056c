// Multigrid Poisson solver for the projection step (see pressure.h).
#include "pressure.h"

#include "parallel.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace meadow {

namespace {
constexpr int kPreSweeps = 2;
constexpr int kPostSweeps = 2;
constexpr int kCoarsestSweeps = 40;
} // namespace

PressureSolver::PressureSolver(glm::ivec3 cells, const std::array<bool, 6>& dirichletFaces) {
    assert(cells.x >= 2 && cells.y >= 2 && cells.z >= 2);
    assert(std::find(dirichletFaces.begin(), dirichletFaces.end(), true) != dirichletFaces.end());
    glm::ivec3 n = cells;
    while (true) {
        Level level;
        level.cells = n;
        level.strideY = n.x + 2;
        level.strideZ = (n.x + 2) * (n.y + 2);
        size_t padded = static_cast<size_t>(n.x + 2) * (n.y + 2) * (n.z + 2);
        level.phi.assign(padded, 0.0f);
        level.rhs.assign(padded, 0.0f);
        level.residual.assign(padded, 0.0f);
        level.diag.assign(padded, 0.0f);
        level.inverseDiag.assign(padded, 0.0f);
        level.slabMax.assign(static_cast<size_t>(n.z), 0.0f);
        for (int k = 0; k < n.z; ++k) {
            for (int j = 0; j < n.y; ++j) {
                for (int i = 0; i < n.x; ++i) {
                    // Interior neighbours count 1. An open face's ghost phi = 0 lies half a fine
                    // cell beyond the face, i.e. delta = 1/2 + 1/2^(level+1) coarse cells from
                    // this cell's centre, and weighs 1 / delta, so every level puts the
                    // Dirichlet condition in the same place. Walls add nothing.
                    float open = 1.0f / (0.5f + 0.5f / static_cast<float>(1 << levels_.size()));
                    float count = 0.0f;
                    count += i > 0 ? 1.0f : (dirichletFaces[0] ? open : 0.0f);
                    count += i < n.x - 1 ? 1.0f : (dirichletFaces[1] ? open : 0.0f);
                    count += j > 0 ? 1.0f : (dirichletFaces[2] ? open : 0.0f);
                    count += j < n.y - 1 ? 1.0f : (dirichletFaces[3] ? open : 0.0f);
                    count += k > 0 ? 1.0f : (dirichletFaces[4] ? open : 0.0f);
                    count += k < n.z - 1 ? 1.0f : (dirichletFaces[5] ? open : 0.0f);
                    size_t c = level.index(i, j, k);
                    level.diag[c] = count;
                    level.inverseDiag[c] = 1.0f / count;
                }
            }
        }
        levels_.push_back(std::move(level));
        bool even = n.x % 2 == 0 && n.y % 2 == 0 && n.z % 2 == 0;
        if (!even || n.x < 4 || n.y < 4 || n.z < 4) {
            break;
        }
        n /= 2;
    }
}

// Red-black Gauss-Seidel: cells of one colour depend only on the other colour, so each half-sweep
// is a set of independent updates, deterministic under any thread count.
void PressureSolver::smooth(Level& level, int sweeps) {
    const glm::ivec3 n = level.cells;
    const size_t sy = static_cast<size_t>(level.strideY);
    const size_t sz = static_cast<size_t>(level.strideZ);
    for (int sweep = 0; sweep < sweeps; ++sweep) {
        for (int colour = 0; colour < 2; ++colour) {
            forEachSlab(n.z, n.x * n.y / 2, [&](int k0, int k1) {
                float* phi = level.phi.data();
                const float* rhs = level.rhs.data();
                const float* inverseDiag = level.inverseDiag.data();
                for (int k = k0; k < k1; ++k) {
                    for (int j = 0; j < n.y; ++j) {
                        int i0 = (colour + j + k) & 1;
                        size_t c = level.index(i0, j, k);
                        for (int i = i0; i < n.x; i += 2, c += 2) {
                            float sum = phi[c - 1] + phi[c + 1] + phi[c - sy] + phi[c + sy] + phi[c - sz] + phi[c + sz];
                            phi[c] = (rhs[c] + sum) * inverseDiag[c];
                        }
                    }
                }
            });
        }
    }
}

float PressureSolver::computeResidual(Level& level) {
    const glm::ivec3 n = level.cells;
    const size_t sy = static_cast<size_t>(level.strideY);
    const size_t sz = static_cast<size_t>(level.strideZ);
    // One maximum per slab, combined in slab order: max is exact, so this is deterministic anyway.
    float* slabMax = level.slabMax.data();
    forEachSlab(n.z, n.x * n.y, [&](int k0, int k1) {
        const float* phi = level.phi.data();
        const float* rhs = level.rhs.data();
        const float* diag = level.diag.data();
        float* residual = level.residual.data();
        for (int k = k0; k < k1; ++k) {
            float maxAbs = 0.0f;
            for (int j = 0; j < n.y; ++j) {
                size_t c = level.index(0, j, k);
                for (int i = 0; i < n.x; ++i, ++c) {
                    float sum = phi[c - 1] + phi[c + 1] + phi[c - sy] + phi[c + sy] + phi[c - sz] + phi[c + sz];
                    float r = rhs[c] - (diag[c] * phi[c] - sum);
                    residual[c] = r;
                    maxAbs = std::max(maxAbs, std::abs(r));
                }
            }
            slabMax[k] = maxAbs;
        }
    });
    float maxAbs = 0.0f;
    for (int k = 0; k < n.z; ++k) {
        maxAbs = std::max(maxAbs, slabMax[k]);
    }
    return maxAbs;
}

// Full weighting for cell-centred grids: the coarse right-hand side is the sum of the 8 children's
// residuals times 1/2 (the -h^2 scaling quadruples from h to 2h, the average divides by 8).
void PressureSolver::restrictResidual(const Level& fine, Level& coarse) {
    const glm::ivec3 n = coarse.cells;
    const size_t fy = static_cast<size_t>(fine.strideY);
    const size_t fz = static_cast<size_t>(fine.strideZ);
    forEachSlab(n.z, n.x * n.y * 8, [&](int k0, int k1) {
        const float* r = fine.residual.data();
        for (int k = k0; k < k1; ++k) {
            for (int j = 0; j < n.y; ++j) {
                for (int i = 0; i < n.x; ++i) {
                    size_t f = fine.index(2 * i, 2 * j, 2 * k);
                    float sum = r[f] + r[f + 1] + r[f + fy] + r[f + fy + 1] + r[f + fz] + r[f + fz + 1] +
                                r[f + fz + fy] + r[f + fz + fy + 1];
                    size_t c = coarse.index(i, j, k);
                    coarse.rhs[c] = 0.5f * sum;
                    coarse.phi[c] = 0.0f;
                }
            }
        }
    });
}

// Trilinear interpolation between cell centres (weights 3/4 and 1/4 per axis); at the grid's edge
// the missing neighbour is replaced by the parent itself.
void PressureSolver::prolongAdd(const Level& coarse, Level& fine) {
    const glm::ivec3 n = fine.cells;
    const glm::ivec3 m = coarse.cells;
    forEachSlab(n.z, n.x * n.y, [&](int k0, int k1) {
        float* phi = fine.phi.data();
        for (int k = k0; k < k1; ++k) {
            int K = k >> 1;
            int K2 = std::clamp(K + ((k & 1) ? 1 : -1), 0, m.z - 1);
            for (int j = 0; j < n.y; ++j) {
                int J = j >> 1;
                int J2 = std::clamp(J + ((j & 1) ? 1 : -1), 0, m.y - 1);
                // The four coarse rows around this fine row, pre-blended in y and z: 9/16, 3/16,
                // 3/16, 1/16.
                const float* r00 = &coarse.phi[coarse.index(0, J, K)];
                const float* r10 = &coarse.phi[coarse.index(0, J2, K)];
                const float* r01 = &coarse.phi[coarse.index(0, J, K2)];
                const float* r11 = &coarse.phi[coarse.index(0, J2, K2)];
                float* out = &phi[fine.index(0, j, k)];
                for (int i = 0; i < n.x; ++i) {
                    int I = i >> 1;
                    int I2 = std::clamp(I + ((i & 1) ? 1 : -1), 0, m.x - 1);
                    float a = 0.5625f * r00[I] + 0.1875f * r10[I] + 0.1875f * r01[I] + 0.0625f * r11[I];
                    float b = 0.5625f * r00[I2] + 0.1875f * r10[I2] + 0.1875f * r01[I2] + 0.0625f * r11[I2];
                    out[i] += 0.75f * a + 0.25f * b;
                }
            }
        }
    });
}

void PressureSolver::vCycle(size_t levelIndex) {
    Level& level = levels_[levelIndex];
    if (levelIndex + 1 == levels_.size()) {
        smooth(level, kCoarsestSweeps);
        return;
    }
    smooth(level, kPreSweeps);
    computeResidual(level);
    restrictResidual(level, levels_[levelIndex + 1]);
    vCycle(levelIndex + 1);
    prolongAdd(levels_[levelIndex + 1], level);
    smooth(level, kPostSweeps);
}

// The first cycle runs unconditionally: after advection the warm start is never already converged,
// so checking first would only cost a residual pass.
int PressureSolver::solve(float tolerance, int maxCycles) {
    int cycles = 0;
    while (true) {
        if (cycles < maxCycles) {
            vCycle(0);
            ++cycles;
        }
        lastMaxResidual_ = computeResidual(levels_[0]);
        if (lastMaxResidual_ <= tolerance || cycles >= maxCycles) {
            return cycles;
        }
    }
}

} // namespace meadow
