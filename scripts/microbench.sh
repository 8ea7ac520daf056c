#!/usr/bin/env bash
# Micro-benchmarks of the precompute's hot CPU paths (precompute/benchmarks, Google Benchmark):
# rod step, fluid step, Embree ray casting of the bake, QEM collapses. Installs what is missing,
# builds meadow_microbench with optimisations (RelWithDebInfo, as `meadow precompute` is built),
# prints the console table and writes the same results as JSON into out/.
#   scripts/microbench.sh [--build-dir DIR] [Google Benchmark flags...]
#     e.g. scripts/microbench.sh --benchmark_filter=fluid --benchmark_repetitions=5
# --build-dir reuses an existing build (its own build type; default: build-bench, configured here).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-bench"
if [ "${1:-}" = "--build-dir" ]; then
  [ $# -ge 2 ] || { echo "microbench.sh: --build-dir needs a folder" >&2; exit 2; }
  build="$(cd "$2" && pwd)"
  shift 2
fi

bash "$root/scripts/install-deps.sh"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
# Only the benchmark and the precompute libraries it links, not the engine and its shaders.
cmake --build "$build" --target meadow_microbench --parallel "$(nproc)"

out="$root/out"
mkdir -p "$out"
json="$out/microbench-$(date +%Y%m%d-%H%M%S).json"
"$build/precompute/benchmarks/meadow_microbench" --benchmark_out="$json" --benchmark_out_format=json "$@"
echo "meadow: results written to $json"
