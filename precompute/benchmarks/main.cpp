// meadow_microbench: Google Benchmark micro-benchmarks of the precompute's hot CPU paths
// (issue 9): the rod substep (sim/), the wind solver's step (wind/), Embree ray casting of the
// light-transfer bake (transfer/) and quadric simplification to the LOD budgets (lod/).
// Every input is real: the default scene's first procedural iris clump at the ci or full
// tessellation, built once outside the timed loops (fixtures.h).
//
//   meadow_microbench [Google Benchmark flags]     e.g. --benchmark_filter=fluid
//   scripts/microbench.sh                          Release-like build, JSON into out/
//
// Exits non-zero when any benchmark failed (an exception from the code under test, a non-finite
// state), so the ctest smoke test catches benchmarks that no longer run.
#include "fixtures.h"

#include <cstdio>

int main(int argc, char** argv) {
    meadow::bench::registerRodBenchmarks();
    meadow::bench::registerFluidBenchmarks();
    meadow::bench::registerRayBenchmarks();
    meadow::bench::registerQemBenchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv))
        return 2;
    const size_t ran = benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    if (meadow::bench::failureCount() > 0) {
        std::fprintf(stderr, "meadow_microbench: %d benchmark(s) failed\n", meadow::bench::failureCount());
        return 1;
    }
    if (ran == 0) {
        std::fprintf(stderr, "meadow_microbench: no benchmark matched the filter\n");
        return 1;
    }
    return 0;
}
