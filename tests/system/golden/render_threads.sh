#!/usr/bin/env bash
# Determinism across thread counts: lavapipe spreads compute workgroups and raster tiles over
# LP_NUM_THREADS threads; the frames must be the same bytes with 1, 2 and 4 of them, for the
# default view and one among the clumps, over three animated frames (FILE.0000.png ...).
#   render_threads.sh MEADOW SCENE OUTDIR
set -euo pipefail
meadow="$1"; scene="$2"; out="$3"
mkdir -p "$out"
for view in default low; do
  camera=()
  [ "$view" = low ] && camera=(--camera 0.3,0.45,-4,2,0.35,3)
  for threads in 1 2 4; do
    LP_NUM_THREADS=$threads "$meadow" render "$scene" --preset ci --size 200x120 --time-of-day 10 --frames 3 \
      "${camera[@]}" --out "$out/threads-$view-$threads.png"
  done
  for threads in 2 4; do
    for frame in 0000 0001 0002; do
      cmp "$out/threads-$view-1.$frame.png" "$out/threads-$view-$threads.$frame.png" ||
        { echo "frame $frame of the $view view differs between 1 and $threads threads"; exit 1; }
    done
  done
done
