#!/usr/bin/env bash
# The walkthrough under Xvfb with a window manager (openbox, so that minimising and fullscreen mean
# something), driven by a scripted input sequence (tests/data/walkthrough/walkthrough.txt): it flies,
# looks, walks, takes screenshots, resizes, toggles vsync, wind, time of day, LOD colours, culling
# freeze and fullscreen, minimises and restores, records a camera path while another plays, and
# quits with Escape, the validation layer on. Then: the camera went where the script sent it
# (window_check.py), the screenshots show pictures at the sizes of the moment, the process exited
# 0 with zero validation messages, and meadow render flies the recorded path.
#   window_test.sh MEADOW IMAGE_COMPARE OUTDIR SCENE
set -euo pipefail
meadow="$1"; compare="$2"; outdir="$3"; scene="$4"
here="$(cd "$(dirname "$0")" && pwd)"
data="$here/../../data/walkthrough"
command -v xvfb-run >/dev/null || { echo "xvfb-run is missing (Debian package xvfb)"; exit 1; }
command -v openbox >/dev/null || { echo "openbox is missing (Debian package openbox)"; exit 1; }
rm -rf "$outdir"
mkdir -p "$outdir/shots"
log="$outdir/window.log"
recorded="$outdir/recorded.path.json"

set +e
xvfb-run -a -s "-screen 0 1024x768x24" bash -c '
  openbox >/dev/null 2>&1 & wm=$!
  sleep 0.5
  "$0" view "$1" --preset ci --size 400x240 --camera=-3,2.2,-17,2,0.2,0 --script "$2/walkthrough.txt" \
    --camera-path "$2/line.json" --record-path "$3" --out-dir "$4/shots" --screenshot "$4/exit.png" --validation
  status=$?
  kill $wm 2>/dev/null
  exit $status' "$meadow" "$scene" "$data" "$recorded" "$outdir" >"$log" 2>&1
status=$?
set -e
cat "$log"
[ "$status" -eq 0 ] || { echo "FAIL: meadow view exited $status"; exit 1; }

python3 "$here/window_check.py" "$log" "$recorded"

# F12 at frame 53 (400x240) and at frame 58 (after the resize to 320x200), and the one at exit.
shot() { compgen -G "$outdir/shots/meadow-*-f$1.png" | head -1 || true; }
first="$(shot 53)"; second="$(shot 58)"
[ -n "$first" ] || { echo "FAIL: no screenshot of frame 53 in $outdir/shots"; ls "$outdir/shots"; exit 1; }
[ -n "$second" ] || { echo "FAIL: no screenshot of frame 58 in $outdir/shots"; ls "$outdir/shots"; exit 1; }
"$compare" "$first" --not-blank --size 400x240
"$compare" "$second" --not-blank --size 320x200
"$compare" "$outdir/exit.png" --not-blank --size 320x200

# The path the walkthrough recorded drives meadow render.
"$meadow" render "$scene" --preset ci --camera-path "$recorded" --frames 2 --size 64x36 --out "$outdir/recorded.png"
"$compare" "$outdir/recorded.0001.png" --not-blank --size 64x36
echo "window test: passed"
