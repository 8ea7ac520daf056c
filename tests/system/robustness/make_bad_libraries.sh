#!/usr/bin/env bash
# The corpus's bad libraries: the micro scene's library, mutated by mutate_library.py into one
# file per CASE, and the library fuzzer's seed (that library with a 1 x 1 atlas) beside them.
#   make_bad_libraries.sh MEADOW MICRO_SCENE OUTDIR MAKE_SEED CASE...
set -euo pipefail
meadow="$1"; micro="$2"; out="$3"; make_seed="$4"
shift 4
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$out" "$out/seed"
"$meadow" precompute "$micro" --preset ci --out "$out/good.mlib" >/dev/null 2>&1
python3 "$here/mutate_library.py" "$out/good.mlib" "$out" "$@"
"$make_seed" "$micro" "$out/seed/micro-tiny-atlas.mlib"
