// The wind solver (precompute/wind): one WindSolver::step of 1/30 s, the step simulateClumpLevel
// takes once per recorded frame (advection, ground stress, boundaries, multigrid projection), on
// the grid both presets use (sim/clump_sim.h: ClumpSimSettings::grid is FluidGrid's default
// 24 x 20 x 24 cells of 8 cm; scene.cpp sets no grid), in calm and strong wind: the projection's
// V-cycles grow with the speed. Parallel inside (TBB), so timed in wall-clock time.
#include "fixtures.h"

#include "wind/fluid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>

namespace meadow::bench {
namespace {

constexpr float kFrameDt = 1.0f / 30.0f; // the motion frame rate of both presets

// Stepped in place: the field keeps evolving with the inflow's gusts and turbulence, statistically
// steady after the first second, which the setup simulates.
WindSolver& windSolver(float speed) {
    static std::mutex mutex;
    static std::map<float, std::unique_ptr<WindSolver>> solvers;
    std::lock_guard<std::mutex> lock(mutex);
    std::unique_ptr<WindSolver>& slot = solvers[speed];
    if (!slot) {
        WindLevelParams level;
        level.direction = glm::normalize(glm::vec3(1.0f, 0.0f, 0.25f)); // irises.json
        level.meanSpeed = speed;
        level.turbulence = 0.3f;
        auto solver = std::make_unique<WindSolver>(FluidGrid{}, level);
        for (int i = 0; i < 30; ++i)
            solver->step(kFrameDt);
        slot = std::move(solver);
    }
    return *slot;
}

void fluidStep(benchmark::State& state, float speed) {
    WindSolver* air = setupOrFail(state, [&]() -> WindSolver& { return windSolver(speed); });
    if (!air)
        return;
    const glm::ivec3 cells = air->grid().cells;
    double cycles = 0.0;
    for (auto _ : state) {
        air->step(kFrameDt);
        cycles += air->lastPressureCycles();
        benchmark::ClobberMemory();
    }
    const double energy = air->kineticEnergy();
    if (!std::isfinite(energy) || !std::isfinite(air->maxDivergence()))
        return fail(state, "the wind field is not finite after stepping");
    state.SetItemsProcessed(int64_t(state.iterations()) * cells.x * cells.y * cells.z);
    state.counters["vcycles"] = cycles / double(std::max<int64_t>(1, int64_t(state.iterations())));
    char label[128];
    std::snprintf(label, sizeof label, "%dx%dx%d cells of %.0f cm, %.1f m/s, dt 1/30 s; items = cells", cells.x,
                  cells.y, cells.z, double(air->grid().cellSize) * 100.0, double(speed));
    state.SetLabel(label);
}

} // namespace

void registerFluidBenchmarks() {
    const FluidGrid grid;
    char name[64];
    for (float speed : {0.7f, 7.0f}) { // the default scene's calmest and strongest levels
        std::snprintf(name, sizeof name, "fluid_step/%dx%dx%d/%.1fmps", grid.cells.x, grid.cells.y, grid.cells.z,
                      double(speed));
        benchmark::RegisterBenchmark(name, [speed](benchmark::State& s) { fluidStep(s, speed); })->UseRealTime();
    }
}

} // namespace meadow::bench
