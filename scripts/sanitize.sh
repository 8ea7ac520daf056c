#!/usr/bin/env bash
# meadow under AddressSanitizer and UndefinedBehaviorSanitizer (docs/ROBUSTNESS.md): builds in
# build-asan with the project's compiler (GCC, as the main build), then runs under the sanitizers
#   - the unit tests (CPU only; ctest label unit, which includes the fuzzers' replays),
#   - the bad-input corpus (label corpus: every bad scene, plant, sky map and library),
#   - a small precompute and inspect through the command line (tests/data/scenes/tiny.json).
# Any sanitizer report aborts the process that made it, so it fails its test.
#   scripts/sanitize.sh [extra ctest arguments...]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-asan"
start=$(date +%s)
bash "$root/scripts/install-deps.sh"
# -O1 with line tables: half the compile time of -O2 -g under the sanitizers, stack traces with
# lines; assertions stay on (no NDEBUG), programmer errors are looked for too.
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" -DMEADOW_SANITIZE=ON >/dev/null
cmake --build "$build" --parallel "$(nproc)"
echo "meadow: sanitizer build ready after $(( $(date +%s) - start )) s" >&2

# Leaks are reported at exit (LeakSanitizer); undefined behaviour stops at the first report.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$root/tests/system/robustness/lsan.supp:print_suppressions=0"

cd "$build"
ctest --output-on-failure --parallel "$(nproc)" -L "unit|corpus" "$@"

out="$build/test-output/sanitize"
mkdir -p "$out"
lib="$out/tiny.mlib"
rm -f "$lib"
MEADOW_CACHE_DIR="$out/cache" ./engine/meadow precompute "$root/tests/data/scenes/tiny.json" --preset ci --out "$lib"
./engine/meadow inspect "$lib" --json >"$out/tiny-inspect.json"
python3 -c 'import json, sys; j = json.load(open(sys.argv[1])); assert j["field"]["clumps"] > 0 and len(j["clumps"]) == 1' \
  "$out/tiny-inspect.json"
echo "meadow: sanitizers found nothing ($(( $(date +%s) - start )) s in all)" >&2
