#!/usr/bin/env bash
# A camera path sets the camera exactly: the first frame rendered along PATH is byte for byte the
# frame of its first keyframe's pose given with --camera (data/paths/flyover.json starts at eye
# -78,16,-80 looking at -10,0,-10).
#   camera_path_drives_render.sh MEADOW SCENE PATH OUTDIR
set -euo pipefail
meadow="$1"; scene="$2"; path="$3"; out="$4"
mkdir -p "$out"
"$meadow" render "$scene" --preset ci --size 96x54 --camera-path "$path" --frames 1 --out "$out/path-a.png"
"$meadow" render "$scene" --preset ci --size 96x54 --camera=-78,16,-80,-10,0,-10 --out "$out/path-b.png"
cmp "$out/path-a.png" "$out/path-b.png"
