// Inputs of meadow_microbench, built once per preset and kept (outside every timed loop): the
// default scene's first procedural iris clump (data/scenes/irises.json, seed 2004, clump 0, the
// clump docs/BENCHMARKS.md reports on) at the ci or full tessellation.
#pragma once

#include "plants/plant.h"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <exception>
#include <string>

namespace meadow::bench {

inline constexpr const char* kPresets[] = {"ci", "full"};
inline constexpr uint64_t kSceneSeed = 2004; // data/scenes/irises.json

// makeIrisClumps(kSceneSeed, 1, irisParamsForPreset(preset))[0], as the library builds clump 0.
const PlantClump& irisClump(const std::string& preset);

// "ci: 1,788 vertices, 1,856 triangles, 37 rods, 271 nodes"
std::string describeClump(const std::string& preset);

// Marks the benchmark as failed: SkipWithError (the library stops its loop and reports the
// message) and a count that main() turns into a non-zero exit, so that the ctest smoke test fails.
// After a call inside the timed loop, break out of it.
void fail(benchmark::State& state, const std::string& message);
int failureCount();

// Runs `setup` (which may throw meadow::Error from the code under test) and returns its result,
// or null after fail() with the message.
template <typename Setup> auto setupOrFail(benchmark::State& state, Setup&& setup) -> decltype(&setup()) {
    try {
        return &setup();
    } catch (const std::exception& e) {
        fail(state, std::string("setup: ") + e.what());
        return nullptr;
    }
}

// Registration, one function per file (main.cpp calls them in order).
void registerRodBenchmarks();
void registerFluidBenchmarks();
void registerRayBenchmarks();
void registerQemBenchmarks();

} // namespace meadow::bench
