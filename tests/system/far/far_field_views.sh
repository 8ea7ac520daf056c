#!/usr/bin/env bash
# The far field against the truth (every clump at full detail, --lod0) in three views of the ci
# field: the default camera, a low view across the field and a high oblique one. Per view five
# renders of one frame: the truth, the far field (under the validation layer), the LOD meshes
# alone (the reference: what the far field replaces), and the LOD view of the truth and of the far
# field (plants told from the ground; the far field's colour marks its region); and the far field
# again on one lavapipe thread, which must give the same bytes. Over the region
# meadow_far_compare checks mean colour, plant coverage and SSIM (docs/BENCHMARKS.md, The far
# field, gives the figures and why these bounds): they guard today's far field against getting
# worse; issue 18's targets (colour within 3 %, coverage within 5 %) are not met yet.
#   far_field_views.sh MEADOW FAR_COMPARE SCENE OUTDIR [SIZE] [FAR_RADIUS]
set -euo pipefail
meadow="$1"; compare="$2"; scene="$3"; out="$4"; size="${5:-480x270}"; radius="${6:-7}"
mkdir -p "$out"
views=("default:" "low:-14,0.7,-14,10,0.5,8" "high:-22,16,-22,4,0,4")
status=0
for view in "${views[@]}"; do
  name="${view%%:*}"; camera="${view#*:}"
  cam=(); [[ -n "$camera" ]] && cam=(--camera "$camera")
  render() {
    "$meadow" render "$scene" --preset ci --size "$size" "${cam[@]}" --out "$out/$name-$1.png" "${@:2}" \
      2>"$out/$name-$1.log" || { cat "$out/$name-$1.log"; echo "far_field_views: $name-$1 failed"; exit 1; }
  }
  render truth --lod0
  render truth-lod --lod0 --debug-lod
  render far --far-radius "$radius" --validation
  render far-lod --far-radius "$radius" --debug-lod
  render meshes
  grep -q "in the far field" "$out/$name-far.log"
  # The visibility buffer's ties resolve the same way whatever the threads do: the same bytes on
  # one lavapipe thread as on all of them.
  LP_NUM_THREADS=1 render far-1thread --far-radius "$radius"
  cmp "$out/$name-far.png" "$out/$name-far-1thread.png" || { echo "far_field_views: $name differs on one thread"; status=1; }
  echo -n "$name: "
  "$compare" "$out/$name-truth.png" "$out/$name-truth-lod.png" "$out/$name-far.png" "$out/$name-far-lod.png" \
    "$out/$name-far-lod.png" --reference "$out/$name-meshes.png" --max-colour 0.25 --coverage-ratio 0.6,2.2 \
    --ssim-margin 0.16 || status=1
done
exit $status
