#!/usr/bin/env bash
# Determinism: the library does not depend on how many threads built it (TBB follows the CPU
# affinity that taskset sets).
#   precompute_threads.sh MEADOW SCENE OUTDIR
set -euo pipefail
meadow="$1"; scene="$2"; out="$3"
mkdir -p "$out"
"$meadow" precompute "$scene" --preset ci --force --out "$out/threads-all.mlib" 2>/dev/null
taskset -c 0 "$meadow" precompute "$scene" --preset ci --force --out "$out/threads-one.mlib" 2>/dev/null
cmp "$out/threads-all.mlib" "$out/threads-one.mlib"
