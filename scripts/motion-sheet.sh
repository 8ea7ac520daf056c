#!/usr/bin/env bash
# An image sheet of each clump's motion (rows: wind levels calm to strong; columns: frames) and
# one of its levels of detail (columns: LOD 0..4; below: the difference from LOD 0), for a person
# to judge the motion library and the LODs. Builds meadow first if needed.
#   scripts/motion-sheet.sh [ci|full]   (default ci)  ->  out/motion-sheet-<clump>.png, out/lod-sheet-<clump>.png
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
preset="${1:-ci}"
bash "$root/scripts/build.sh" "$root/build" -DCMAKE_BUILD_TYPE=Release
mkdir -p "$root/out"
for clump in 0 1 2 3; do
  "$root/build/engine/meadow" sheet "$root/data/scenes/irises.json" --preset "$preset" --clump "$clump" \
    --out "$root/out/motion-sheet-$clump.png"
  "$root/build/engine/meadow" sheet "$root/data/scenes/irises.json" --preset "$preset" --clump "$clump" \
    --lods --out "$root/out/lod-sheet-$clump.png"
done
echo "meadow: motion and LOD sheets written to $root/out"
