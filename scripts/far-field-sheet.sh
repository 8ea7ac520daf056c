#!/usr/bin/env bash
# The far field for review: the three views of tests/system/far/far_field_views.sh (default, low
# across the field, high oblique) at a larger size, each as a row of truth (every clump at LOD 0),
# the far field's reference (its clumps as LOD 0 meshes, --far-lod0), the far field, the LOD meshes
# alone and the far field's LOD view (cyan: the far field), into one sheet.
#   scripts/far-field-sheet.sh [SCENE] [OUTDIR] [SIZE] [FAR_RADIUS] [PRESET]
# FAR_RADIUS defaults to "default": meadow's own (28 px), as `render` draws without --far-radius.
# MEADOW=path/to/meadow uses that build (default: build/engine/meadow, built Release if missing).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
scene="${1:-$root/data/scenes/irises.json}"; out="${2:-$root/out/far-field}"; size="${3:-960x540}"
radius="${4:-default}"; preset="${5:-ci}"
meadow="${MEADOW:-$root/build/engine/meadow}"
[[ -x "$meadow" ]] || bash "$root/scripts/build.sh" "$root/build" -DCMAKE_BUILD_TYPE=Release >&2
mkdir -p "$out"
views=("default:" "low:-30,1.2,-30,0,0.4,0" "high:-22,16,-22,4,0,4")
far=(--far-radius "$radius"); [[ "$radius" == default ]] && far=()
rows=()
for view in "${views[@]}"; do
  name="${view%%:*}"; camera="${view#*:}"
  cam=(); [[ -n "$camera" ]] && cam=(--camera "$camera")
  for kind in truth reference far meshes far-lod; do
    case "$kind" in
      truth) extra=(--lod0) ;; reference) extra=("${far[@]}" --far-lod0) ;;
      far) extra=("${far[@]}") ;; meshes) extra=(--far-radius 0) ;;
      far-lod) extra=("${far[@]}" --debug-lod) ;;
    esac
    "$meadow" render "$scene" --preset "$preset" --size "$size" "${cam[@]}" "${extra[@]}" \
      --out "$out/$name-$kind.png" 2>/dev/null
    rows+=("$out/$name-$kind.png")
  done
done
oiiotool "${rows[@]}" --mosaic 5x3 -o "$out/sheet.png"
echo "$out/sheet.png (columns: truth, the far field's reference, far field, LOD meshes, far field in the LOD view;" \
  "rows: default, low, high)"
