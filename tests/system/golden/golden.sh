#!/usr/bin/env bash
# Golden-image tests: each case renders a small image and compares it with the committed golden
# in tests/system/golden/images/, with a tolerance kept beside the case and the reason for it.
# On failure the actual and difference images are written to OUTDIR.
#
#   golden.sh MEADOW IMAGE_COMPARE OUTDIR CASE             compare (what ctest runs)
#   golden.sh MEADOW IMAGE_COMPARE OUTDIR CASE --approve   overwrite the golden (scripts/approve-goldens.sh)
#   golden.sh --list                                       the case names
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
scene="$here/../../../data/scenes/irises.json"

# Each case: meadow render arguments, then tolerances.
#   threshold: per-channel difference (0-1) above which a pixel counts as failed.
#   percent:   share of pixels allowed to fail.
case_args() {
  case "$1" in
    field_afternoon)
      # The default field (ci preset) in afternoon light: cull -> indirect draw -> far field's
      # splats and resolve (at 160x90 nearly every clump is below the default 28 px) -> tonemap.
      # Reason for the tolerance: lavapipe is pinned to 128-bit vectors so results are stable,
      # but LLVM may pick other instructions for pow/exp on other CPUs; a few edge pixels of
      # thin blades may flip. A missing pass or a wrong barrier changes far more than 0.5%.
      args=(render "$scene" --preset ci --size 160x90)
      threshold=0.04; percent=0.5 ;;
    field_afternoon_meshes)
      # The same frame without the far field (--far-radius 0): every clump as its LOD mesh, most
      # of them LOD 3 and 4 at this size.
      args=(render "$scene" --preset ci --size 160x90 --far-radius 0)
      threshold=0.04; percent=0.5 ;;
    field_morning_high)
      # Low sun, camera high above the field looking down: exercises culling with a steep
      # frustum and the sun-colour path. Same tolerance reasoning as above.
      args=(render "$scene" --preset ci --size 160x90 --time-of-day 7.5 --camera -20,25,-20,0,0,0)
      threshold=0.04; percent=0.5 ;;
    calm_noon)
      # Noon, no wind: the sky's SH through the light pass, clumps near their calm frames.
      args=(render "$scene" --preset ci --size 160x90 --time-of-day 12 --wind 0)
      threshold=0.04; percent=0.5 ;;
    windy_evening)
      # Strong wind in low evening light: the animate pass walks the clumps into the top wind
      # level for 2 s before the frame; a warm, dim sky and its exposure.
      args=(render "$scene" --preset ci --size 160x90 --time-of-day 18.5 --wind 3)
      threshold=0.04; percent=0.5 ;;
    low_camera)
      # Eye at knee height among the clumps: LOD 0 up close, blades and petals alpha-tested,
      # both sides of the sheets lit, rocks.
      args=(render "$scene" --preset ci --size 160x90 --time-of-day 10 --camera 0.3,0.45,-4,2,0.35,3)
      threshold=0.04; percent=0.8 ;;
    lod_colors)
      # The LOD debug view: each clump in its level of detail's colour (red 0 .. violet 4), without
      # the far field (which --debug-lod shows in cyan: far.views covers it).
      args=(render "$scene" --preset ci --size 160x90 --debug-lod --far-radius 0)
      threshold=0.04; percent=0.5 ;;
    lod_sheet)
      # One clump at each level of detail, and the differences (meadow sheet --lods), validated.
      args=(sheet "$scene" --preset ci --clump 2 --lods --cell 64x64 --validation)
      threshold=0.04; percent=0.5 ;;
    motion_sheet)
      # One clump at every wind level, played from its motion basis (meadow sheet), validated.
      args=(sheet "$scene" --preset ci --clump 1 --columns 3 --cell 64x64 --validation)
      threshold=0.04; percent=0.5 ;;
    *) echo "golden.sh: unknown case '$1'" >&2; exit 2 ;;
  esac
}

if [ "${1:-}" = "--list" ]; then
  echo field_afternoon field_afternoon_meshes field_morning_high calm_noon windy_evening low_camera lod_colors lod_sheet motion_sheet
  exit 0
fi

meadow="$1"; compare="$2"; outdir="$3"; name="$4"; mode="${5:-}"
case_args "$name"
golden="$here/images/$name.png"
mkdir -p "$outdir"
actual="$outdir/$name.actual.png"
rm -f "$actual" "$outdir/$name.diff.png"

"$meadow" "${args[@]}" --out "$actual"

if [ "$mode" = "--approve" ]; then
  cp "$actual" "$golden"
  echo "approved $golden"
  exit 0
fi
if [ ! -f "$golden" ]; then
  echo "golden.sh: no golden image $golden; render and review it, then run scripts/approve-goldens.sh" >&2
  exit 1
fi
if "$compare" "$actual" "$golden" --fail-threshold "$threshold" --fail-percent "$percent" --diff "$outdir/$name.diff.png"; then
  rm -f "$actual"
else
  echo "golden.sh: actual image kept at $actual" >&2
  exit 1
fi
