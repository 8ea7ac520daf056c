#!/usr/bin/env bash
# The walkthrough under Xvfb with a window manager (openbox, so that minimising means something):
# opens the window, renders frames, resizes it, minimises and restores it, writes a screenshot
# and exits 0 with the validation layer on and silent.
#   window_test.sh MEADOW IMAGE_COMPARE OUTDIR SCENE
set -euo pipefail
meadow="$1"; compare="$2"; outdir="$3"; scene="$4"
command -v xvfb-run >/dev/null || { echo "xvfb-run is missing (Debian package xvfb)"; exit 1; }
command -v openbox >/dev/null || { echo "openbox is missing (Debian package openbox)"; exit 1; }
mkdir -p "$outdir"
shot="$outdir/window.png"
log="$outdir/window.log"
rm -f "$shot"
xvfb-run -a -s "-screen 0 1024x768x24" bash -c '
  openbox >/dev/null 2>&1 & wm=$!
  sleep 0.5
  "$0" view "$1" --preset ci --size 400x240 --frames 45 --resize 320x200 --minimize --screenshot "$2" --validation
  status=$?
  kill $wm 2>/dev/null
  exit $status' "$meadow" "$scene" "$shot" 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
[ "$status" -eq 0 ] || { echo "FAIL: meadow view exited $status"; exit 1; }
grep -q "0 messages" "$log" || { echo "FAIL: no validation summary"; exit 1; }
grep -q "view showed 45 frames; window 320x200" "$log" || { echo "FAIL: the resize did not happen"; exit 1; }
grep -q "window minimised; rendering paused" "$log" || { echo "FAIL: the window was not minimised"; exit 1; }
grep -q "window restored; rendering resumed" "$log" || { echo "FAIL: the window was not restored"; exit 1; }
# The screenshot has the resized window's size and shows a picture.
"$compare" "$shot" --not-blank --size 320x200
