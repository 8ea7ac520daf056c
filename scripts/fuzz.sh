#!/usr/bin/env bash
# Fuzzes meadow's loaders with libFuzzer (docs/ROBUSTNESS.md): the scene parser, the glTF import
# path and the library loader, each for SECONDS (CI: 60), under AddressSanitizer and
# UndefinedBehaviorSanitizer. Builds with clang in build-fuzz, only what the fuzzers need (the
# loaders and the precompute libraries; libFuzzer's coverage on the loaders alone).
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     targets: scene gltf library (default all)
# Environment: FUZZ_JOBS=N runs N fuzzing processes per target (longer runs on more cores).
# What the fuzzers learn is kept in build-fuzz/fuzz/corpus/TARGET, so later runs go on from there.
# A crash leaves its input in build-fuzz/fuzz/crashes/ and fails the script; once fixed, the input
# goes into tests/system/fuzz/regressions/TARGET/, which every build replays (tests fuzz.replay_TARGET).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-fuzz"
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene gltf library)
jobs="${FUZZ_JOBS:-1}"
start=$(date +%s)

bash "$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DMEADOW_FUZZ=ON >/dev/null
cmake --build "$build" --parallel "$(nproc)" \
  --target meadow_fuzz_scene meadow_fuzz_gltf meadow_fuzz_library meadow_fuzz_make_seed
echo "meadow: fuzz build ready after $(( $(date +%s) - start )) s" >&2

work="$build/fuzz"
mkdir -p "$work/crashes"
# The library fuzzer's seed: the micro scene's library with a 1 x 1 atlas (37 KB, every section).
mkdir -p "$work/seeds/library"
"$build/tests/system/fuzz/meadow_fuzz_make_seed" "$root/tests/system/robustness/micro.json" "$work/seeds/library/micro.mlib"

declare -A seeds=(
  [scene]="$root/data/scenes $root/tests/data/scenes $root/tests/system/robustness/scenes"
  [gltf]="$root/tests/data/gltf $root/tests/system/robustness/gltf"
  [library]="$work/seeds/library"
)
declare -A max_len=([scene]=16384 [gltf]=16384 [library]=65536)

export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1"
# Leaks inside third-party libraries that meadow cannot free, as in scripts/sanitize.sh.
export LSAN_OPTIONS="suppressions=$root/tests/system/robustness/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
status=0
for target in "${targets[@]}"; do
  corpus="$work/corpus/$target"
  mkdir -p "$corpus"
  for dir in $root/tests/system/fuzz/regressions/$target; do [ -d "$dir" ] && cp -n "$dir"/* "$corpus"/ 2>/dev/null || true; done
  echo "meadow: fuzzing $target for $seconds s ($jobs job(s))" >&2
  parallel=()
  [ "$jobs" -gt 1 ] && parallel=(-jobs="$jobs" -workers="$jobs")
  # The working directory holds nothing to read (each input is written to a scratch folder of its
  # process, fuzz_input.h). Inputs over 10 s, 2 GiB resident or a 1 GiB allocation count as crashes.
  # shellcheck disable=SC2086
  if ! (cd "$work" && "$build/tests/system/fuzz/meadow_fuzz_$target" "$corpus" ${seeds[$target]} \
          -dict="$root/tests/system/fuzz/$target.dict" -max_len="${max_len[$target]}" -max_total_time="$seconds" \
          -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -print_final_stats=1 \
          -artifact_prefix="$work/crashes/$target-" "${parallel[@]}" >"$work/$target.log" 2>&1); then
    status=1
  fi
  logs=("$work/$target.log")
  [ "$jobs" -gt 1 ] && logs=("$work"/fuzz-*.log) # one per worker; the main log repeats them
  cat "${logs[@]}" 2>/dev/null |
    grep -E "^stat::(number_of_executed_units|new_units_added)|^SUMMARY" | sed "s/^/  $target: /" >&2 || true
  rm -f "$work"/fuzz-*.log
done
if compgen -G "$work/crashes/*" >/dev/null; then
  echo "meadow: the fuzzers found inputs that crash (logs in $work/*.log):" >&2
  ls -l "$work/crashes" >&2
  status=1
fi
rm -rf /tmp/meadow-fuzz-*
echo "meadow: fuzzing done in $(( $(date +%s) - start )) s" >&2
exit $status
