#!/usr/bin/env bash
# precompute -> inspect through the command line: the second precompute finds the library up to
# date, and inspect's JSON holds the figures check_inspect.py checks.
#   precompute_inspect.sh MEADOW SCENE OUTDIR
set -euo pipefail
meadow="$1"; scene="$2"; out="$3"
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$out"
lib="$("$meadow" precompute "$scene" --preset ci)"
again="$("$meadow" precompute "$scene" --preset ci 2>&1)"
grep -q "is up to date" <<<"$again" || { echo "the second precompute rebuilt the library:"; echo "$again"; exit 1; }
"$meadow" inspect "$lib" --json >"$out/inspect.json"
python3 "$here/check_inspect.py" "$out/inspect.json"
