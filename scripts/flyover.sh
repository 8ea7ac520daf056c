#!/usr/bin/env bash
# A fly-over of the default field (data/scenes/irises.json) along a camera path
# (data/paths/flyover.json: 15 s from high above a corner down among the irises and up again),
# rendered offscreen into out/flyover/frame.NNNN.png at 30 frames per second, and into
# out/flyover.mp4 when ffmpeg is installed (apt-get install ffmpeg). For a person to look at:
# the same path plays in the walkthrough (meadow view --camera-path FILE, key P).
#   scripts/flyover.sh [--preset ci|full] [--size WxH] [--path FILE] [--meadow BIN]
# --meadow uses an already built meadow instead of installing what is missing and building.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
preset=full
size=1280x720
path="$root/data/paths/flyover.json"
meadow=""
usage() { sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; }
while [ $# -gt 0 ]; do
  case "$1" in
    --preset) preset="${2:?--preset needs ci or full}"; shift 2 ;;
    --size) size="${2:?--size needs WxH}"; shift 2 ;;
    --path) path="${2:?--path needs a camera path file}"; shift 2 ;;
    --meadow) meadow="${2:?--meadow needs the meadow executable}"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "flyover.sh: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
done
[ -f "$path" ] || { echo "flyover.sh: camera path $path: no such file" >&2; exit 1; }

if [ -z "$meadow" ]; then
  bash "$root/scripts/build.sh" "$root/build" -DCMAKE_BUILD_TYPE=Release
  meadow="$root/build/engine/meadow"
fi
[ -x "$meadow" ] || { echo "flyover.sh: $meadow is not an executable" >&2; exit 1; }

out="$root/out/flyover"
mkdir -p "$out"
rm -f "$out"/frame.*.png
# Every frame of the path (meadow render --camera-path renders them all without --frames).
"$meadow" render "$root/data/scenes/irises.json" --preset "$preset" --size "$size" --camera-path "$path" \
  --out "$out/frame.png"
frames=$(ls "$out"/frame.*.png | wc -l)
echo "flyover.sh: $frames frames in $out"

if command -v ffmpeg >/dev/null; then
  video="$root/out/flyover.mp4"
  # H.264 in 4:2:0 wants even sizes.
  ffmpeg -y -loglevel error -framerate 30 -i "$out/frame.%04d.png" -vf "scale=trunc(iw/2)*2:trunc(ih/2)*2" \
    -c:v libx264 -pix_fmt yuv420p -crf 18 "$video"
  echo "flyover.sh: video $video"
else
  echo "flyover.sh: no ffmpeg, so no video (apt-get install ffmpeg, then run this again)"
fi
