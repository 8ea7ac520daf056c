#!/usr/bin/env bash
# Determinism: the same scene and seed give the same frame, byte for byte, on lavapipe; another
# seed gives another frame.
#   determinism.sh MEADOW SCENE OUTDIR
set -euo pipefail
meadow="$1"; scene="$2"; out="$3"
mkdir -p "$out"
for i in 1 2; do
  "$meadow" render "$scene" --preset ci --size 200x120 --time-of-day 10 --out "$out/det-$i.png"
done
cmp "$out/det-1.png" "$out/det-2.png"
"$meadow" render "$scene" --preset ci --seed 7 --size 200x120 --time-of-day 10 --out "$out/det-3.png"
! cmp -s "$out/det-1.png" "$out/det-3.png"
