#!/usr/bin/env bash
# The same frames with and without the device's robust buffer access (MEADOW_ROBUST_BUFFER_ACCESS=1:
# robustBufferAccess and robustBufferAccess2, where reads outside a buffer give zero and writes
# outside it are dropped) must be the same bytes: a pass that reads or writes outside one of its
# buffers would change the picture under it. Golden views at both lavapipe vector widths.
#
#   robust_access.sh MEADOW OUTDIR SCENE
set -euo pipefail
meadow="$1"; outdir="$2"; scene="$3"
mkdir -p "$outdir"
views=(
  "default::--time-of-day 15"
  "low:--camera 0.3,0.45,-4,2,0.35,3:--time-of-day 10"
  "high:--camera -20,25,-20,0,0,0:--time-of-day 7.5"
  "lod:--debug-lod:--wind 3"
)
for width in 128 256; do
  for view in "${views[@]}"; do
    IFS=: read -r name camera extra <<<"$view"
    for robust in 0 1; do
      # shellcheck disable=SC2086 # the view's options are words
      LP_NATIVE_VECTOR_WIDTH=$width MEADOW_ROBUST_BUFFER_ACCESS=$robust \
        "$meadow" render "$scene" --preset ci --size 160x90 --frames 2 $camera $extra \
        --out "$outdir/$name-$width-robust$robust.png" >/dev/null
    done
    for frame in 0000 0001; do # --frames 2 numbers the files
      if ! cmp -s "$outdir/$name-$width-robust0.$frame.png" "$outdir/$name-$width-robust1.$frame.png"; then
        echo "FAILED  view $name at $width bits, frame $frame: the frame changes under robust buffer access"
        exit 1
      fi
    done
    echo "ok      view $name at $width bits: the same bytes with and without robust buffer access"
  done
done
