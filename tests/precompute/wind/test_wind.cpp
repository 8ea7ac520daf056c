// Tests of the wind solver (precompute/wind/fluid.h). Each float comparison states its tolerance
// and why. Step size 1/30 s is the coarsest the simulation uses (30 Hz output).
#include "wind/fluid.h"

#include "core/error.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <vector>

namespace meadow {
namespace {

constexpr float kDt = 1.0f / 30.0f;
// Clump height: irises stand 0.6-1 m; the probe sits at the reference height of the profile,
// above the clump's centre.
const glm::vec3 kProbe{0.0f, 1.0f, 0.0f};

WindLevelParams levelWith(float meanSpeed, float turbulence = 0.25f, uint64_t seed = 1) {
    WindLevelParams level;
    level.meanSpeed = meanSpeed;
    level.turbulence = turbulence;
    level.seed = seed;
    return level;
}

struct ProbeStats {
    double mean = 0.0;
    double std = 0.0;
};

ProbeStats probeSpeed(WindSolver& solver, glm::vec3 probe, int spinUpSteps, int steps) {
    for (int i = 0; i < spinUpSteps; ++i) {
        solver.step(kDt);
    }
    double sum = 0.0;
    double sumSquares = 0.0;
    for (int i = 0; i < steps; ++i) {
        solver.step(kDt);
        double speed = glm::length(solver.velocityAt(probe));
        sum += speed;
        sumSquares += speed * speed;
    }
    ProbeStats stats;
    stats.mean = sum / steps;
    stats.std = std::sqrt(std::max(0.0, sumSquares / steps - stats.mean * stats.mean));
    return stats;
}

// Velocity on a lattice through the whole box, for bitwise comparisons.
std::vector<glm::vec3> sampleField(const WindSolver& solver) {
    std::vector<glm::vec3> samples;
    const FluidGrid& grid = solver.grid();
    for (int k = 0; k <= grid.cells.z; k += 3) {
        for (int j = 0; j <= grid.cells.y; j += 3) {
            for (int i = 0; i <= grid.cells.x; i += 3) {
                samples.push_back(
                    solver.velocityAt(grid.origin + grid.cellSize * glm::vec3(i + 0.3f, j + 0.6f, k + 0.1f)));
            }
        }
    }
    return samples;
}

bool bitIdentical(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)) == 0;
}

// Requirement: max |div u| * h / U < 1e-3 after every projection, along an axis and diagonally
// (two upwind faces), from the first projection on.
TEST(Wind, DivergenceAfterProjectionIsWithinBound) {
    for (glm::vec3 direction : {glm::vec3(1, 0, 0), glm::vec3(-0.6f, 0, 0.8f)}) {
        WindLevelParams level = levelWith(5.0f, 0.4f);
        level.direction = direction;
        WindSolver solver(FluidGrid{}, level);
        double bound = 1e-3 * level.meanSpeed / solver.grid().cellSize;
        EXPECT_LT(solver.maxDivergence(), bound);
        for (int i = 0; i < 60; ++i) {
            solver.step(kDt);
            ASSERT_LT(solver.maxDivergence(), bound) << "step " << i;
            EXPECT_LE(solver.lastPressureCycles(), 12);
        }
    }
}

// The probe at 1 m sees the level's mean speed: 15 % covers turbulence sampling over 3 s and the
// slowdown the ground stress spreads upwards.
TEST(Wind, MeanSpeedAtProbeMatchesLevel) {
    for (float meanSpeed : {0.5f, 2.0f, 5.0f, 9.0f}) {
        WindSolver solver(FluidGrid{}, levelWith(meanSpeed));
        ProbeStats stats = probeSpeed(solver, kProbe, 30, 90);
        EXPECT_NEAR(stats.mean, meanSpeed, 0.15 * meanSpeed) << "level " << meanSpeed << " m/s";
        std::printf("mean speed %.2f m/s: probe mean %.3f m/s (%.1f %%)\n", meanSpeed, stats.mean,
                    100.0 * (stats.mean / meanSpeed - 1.0));
    }
}

// Fluctuations exist and grow with the injected intensity; without injection the flow is steady
// (only numerical noise: std < 1 % of the mean).
TEST(Wind, TurbulenceIsPresentAndGrowsWithIntensity) {
    double previous = -1.0;
    for (float turbulence : {0.0f, 0.1f, 0.25f, 0.4f}) {
        WindSolver solver(FluidGrid{}, levelWith(2.0f, turbulence));
        ProbeStats stats = probeSpeed(solver, kProbe, 30, 240);
        double intensity = stats.std / stats.mean;
        std::printf("turbulence %.2f: probe speed mean %.3f m/s, std %.3f m/s, intensity %.3f\n", turbulence,
                    stats.mean, stats.std, intensity);
        if (turbulence == 0.0f) {
            EXPECT_LT(intensity, 0.01);
        } else {
            EXPECT_GT(intensity, 0.3 * turbulence);
            EXPECT_GT(intensity, previous);
        }
        previous = intensity;
    }
}

// The ground face is solid: the vertical velocity on it is exactly zero everywhere.
TEST(Wind, NoFlowThroughGround) {
    WindSolver solver(FluidGrid{}, levelWith(9.0f, 0.4f));
    for (int i = 0; i < 30; ++i) {
        solver.step(kDt);
    }
    const FluidGrid& grid = solver.grid();
    for (int k = 0; k < grid.cells.z; ++k) {
        for (int i = 0; i < grid.cells.x; ++i) {
            glm::vec3 p = grid.origin + grid.cellSize * glm::vec3(i + 0.37f, 0.0f, k + 0.61f);
            ASSERT_EQ(solver.velocityAt(p).y, 0.0f) << i << ", " << k;
        }
    }
}

TEST(Wind, SameInputsGiveIdenticalBits) {
    auto run = [] {
        WindSolver solver(FluidGrid{}, levelWith(5.0f, 0.4f, 42));
        for (int i = 0; i < 40; ++i) {
            solver.addForce({0.05f, 0.4f, -0.02f}, {-0.1f, 0.02f, 0.0f});
            solver.step(kDt);
        }
        return sampleField(solver);
    };
    EXPECT_TRUE(bitIdentical(run(), run()));
}

TEST(Wind, ThreadCountDoesNotChangeBits) {
    auto run = [](int threads) {
        tbb::global_control control(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
        WindSolver solver(FluidGrid{}, levelWith(5.0f, 0.4f, 7));
        for (int i = 0; i < 40; ++i) {
            solver.addForce({0.05f, 0.4f, -0.02f}, {-0.1f, 0.02f, 0.0f});
            solver.step(kDt);
        }
        return std::make_pair(sampleField(solver), solver.kineticEnergy());
    };
    auto one = run(1);
    auto two = run(2);
    EXPECT_TRUE(bitIdentical(one.first, two.first));
    EXPECT_EQ(one.second, two.second);
}

// 2,000 steps (67 s) of the strongest level at the coarsest step: no NaN, and the energy stays
// within a factor 4 of its start. Gusts alone reach a factor 1 + 0.4 * 0.6 * 2.33 = 1.56 in speed
// (2.4 in energy) and turbulence adds about (0.8 * 0.4)^2; a blow-up grows by orders of magnitude.
TEST(Wind, StrongestLevelStaysStable) {
    WindSolver solver(FluidGrid{}, levelWith(9.0f, 0.4f, 3));
    const double initial = solver.kineticEnergy();
    double maxEnergy = 0.0;
    for (int i = 0; i < 2000; ++i) {
        solver.step(kDt);
        double energy = solver.kineticEnergy();
        ASSERT_TRUE(std::isfinite(energy)) << "step " << i;
        maxEnergy = std::max(maxEnergy, energy);
    }
    EXPECT_LT(maxEnergy, 4.0 * initial);
    EXPECT_GT(solver.kineticEnergy(), 0.3 * initial);
    for (glm::vec3 v : sampleField(solver)) {
        ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
        ASSERT_LT(glm::length(v), 40.0f);
    }
}

// Two-way coupling: a clump-sized drag (0.1 N: 0.5 rho C_d A U^2 with C_d = 0.4, A = 0.1 m^2 at
// 2 m/s) pushed against the wind slows the air behind it by more than 10 %; the same seed without
// it is the reference.
TEST(Wind, ForceAgainstTheFlowSlowsItDownstream) {
    const glm::vec3 downstream{0.3f, 0.5f, 0.0f};
    auto run = [&](bool couple) {
        WindSolver solver(FluidGrid{}, levelWith(2.0f, 0.1f, 5));
        double sum = 0.0;
        for (int i = 0; i < 90; ++i) {
            if (couple) {
                for (int a = -1; a <= 1; ++a) {
                    for (int b = -1; b <= 1; ++b) {
                        solver.addForce({0.0f, 0.5f + 0.1f * a, 0.1f * b}, glm::vec3(-0.1f / 9.0f, 0.0f, 0.0f));
                    }
                }
            }
            solver.step(kDt);
            if (i >= 30) {
                sum += solver.velocityAt(downstream).x;
            }
        }
        return sum / 60.0;
    };
    double free = run(false);
    double coupled = run(true);
    std::printf("downstream speed: free %.3f m/s, with 0.1 N drag %.3f m/s\n", free, coupled);
    EXPECT_LT(coupled, 0.9 * free);
}

// Outside the box the solver returns the ambient wind; with no turbulence that is exactly the
// power-law profile, meanSpeed at 1 m (tolerance: float rounding of pow).
TEST(Wind, OutsideTheBoxIsTheInflowProfile) {
    WindSolver gusty(FluidGrid{}, levelWith(5.0f, 0.3f));
    gusty.step(kDt);
    for (glm::vec3 p : {glm::vec3(-3.0f, 0.7f, 0.2f), glm::vec3(0.0f, 2.5f, 0.0f), glm::vec3(4.0f, 0.3f, 5.0f)}) {
        glm::vec3 a = gusty.velocityAt(p);
        glm::vec3 b = gusty.inflowVelocity(p);
        EXPECT_EQ(a, b);
    }
    WindLevelParams level = levelWith(5.0f, 0.0f);
    level.direction = glm::vec3(0.0f, 0.0f, -2.0f);
    WindSolver steady(FluidGrid{}, level);
    steady.step(kDt);
    EXPECT_NEAR(steady.inflowProfile(1.0f), 5.0f, 1e-5f);
    for (float height : {0.1f, 0.5f, 1.0f, 3.0f}) {
        glm::vec3 v = steady.velocityAt({0.0f, height, 3.0f});
        EXPECT_NEAR(v.x, 0.0f, 1e-6f);
        EXPECT_NEAR(v.y, 0.0f, 1e-6f);
        EXPECT_NEAR(v.z, -5.0f * std::pow(height, 1.0f / 7.0f), 1e-5f);
    }
}

TEST(Wind, RejectsBadInput) {
    FluidGrid grid;
    grid.cellSize = 0.0f;
    EXPECT_THROW(WindSolver(grid, WindLevelParams{}), Error);
    WindLevelParams vertical;
    vertical.direction = {0.0f, 1.0f, 0.0f};
    EXPECT_THROW(WindSolver(FluidGrid{}, vertical), Error);
    EXPECT_THROW(WindSolver(FluidGrid{}, levelWith(-1.0f)), Error);
    WindLevelParams noGusts;
    noGusts.gustPeriod = 0.0f;
    EXPECT_THROW(WindSolver(FluidGrid{}, noGusts), Error);
}

// CPU time of this thread: on a shared machine wall time also counts other processes.
double threadCpuSeconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Timing (not run by default: --gtest_also_run_disabled_tests). Single-threaded, default grid.
TEST(Wind, DISABLED_StepTiming) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, 1);
    for (float meanSpeed : {0.5f, 2.0f, 5.0f, 9.0f}) {
        WindSolver solver(FluidGrid{}, levelWith(meanSpeed, 0.4f));
        for (int i = 0; i < 30; ++i) {
            solver.step(kDt);
        }
        constexpr int kSteps = 600;
        int cycles = 0;
        auto start = std::chrono::steady_clock::now();
        double cpuStart = threadCpuSeconds();
        for (int i = 0; i < kSteps; ++i) {
            solver.step(kDt);
            cycles += solver.lastPressureCycles();
        }
        double cpu = threadCpuSeconds() - cpuStart;
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("%.1f m/s: %.3f ms per step (thread CPU), %.3f ms wall, %.2f V-cycles per step, "
                    "max div * h / U %.2e\n",
                    meanSpeed, 1e3 * cpu / kSteps, 1e3 * seconds / kSteps, static_cast<double>(cycles) / kSteps,
                    solver.maxDivergence() * solver.grid().cellSize / meanSpeed);
    }
}

} // namespace
} // namespace meadow
