#!/usr/bin/env bash
# meadow's main job on the bundled default scene (data/scenes/irises.json): installs what is
# missing, builds, then opens the walkthrough window when a display exists, and otherwise
# renders offscreen frames into out/ (it prints the folder).
#   scripts/run.sh [--offscreen]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build"
bash "$root/scripts/build.sh" "$build" -DCMAKE_BUILD_TYPE=Release
meadow="$build/engine/meadow"
scene="$root/data/scenes/irises.json"

if [ "${1:-}" != "--offscreen" ] && { [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; }; then
  exec "$meadow" view "$scene"
fi

out="$root/out"
mkdir -p "$out"
for hour in 7.5 12 16.5; do
  "$meadow" render "$scene" --size 1280x720 --time-of-day "$hour" --out "$out/irises-${hour}h.png"
done
echo "meadow: frames written to $out"
