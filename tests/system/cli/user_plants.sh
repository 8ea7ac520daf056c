#!/usr/bin/env bash
# User plants (tests/data/gltf, made by make_plants.py): hand-made plants of different size and
# stiffness each build a usable library in the ci preset, with what the motion-graph build adapted
# said in inspect; the textured plant's colours appear in a render; a closed solid is refused.
#   user_plants.sh MEADOW GLTF_DIR OUTDIR
set -euo pipefail
meadow="$1"; gltf="$(cd "$2" && pwd)"; out="$3"
mkdir -p "$out"

scene() { # scene NAME FILE [STEM_DIAMETER]
  python3 - "$out/$1.json" "$1" "$gltf/$2" "${3:-}" <<'PY'
import json, sys
path, name, plant, stem = sys.argv[1:5]
scene = {
    "name": name, "seed": 11,
    "field": {"tilesX": 2, "tilesY": 2, "tileSize": 2.0, "cellSize": 0.05, "rocksPerTile": 0, "sweptFrames": 16},
    "camera": {"eye": [0.0, 1.6, -1.2], "target": [0.0, 0.0, 1.0], "fovYDegrees": 50},
    "timeOfDay": 12.0,
    "plants": {"source": "gltf", "gltf": plant},
    "wind": {"levels": [0.7, 2.0, 4.0, 7.0]},
    "motion": {"settleSeconds": 0.5, "recordSeconds": 2.0},
    "sky": {"frames": 4, "imageWidth": 16},
    "light": {"raysPerVertex": 32, "bounces": 1, "framesPerLevel": 2, "groundGridResolution": 4, "groundRaysPerPoint": 16},
}
if stem:
    scene["plants"]["stemDiameter"] = float(stem)
json.dump(scene, open(path, "w"), indent=1)
PY
}

# name, file, stem diameter (empty: the importer's default, a stem the plant's weight would bend by 10 % of its height held level)
plants=("three_blades three_blades.gltf" "reed_stiff reed.gltf 0.03" "tuft_soft low_tuft.gltf 0.0008"
        "painted painted.gltf")
for entry in "${plants[@]}"; do
  read -r name file stem <<<"$entry"
  scene "$name" "$file" "$stem"
  lib="$("$meadow" precompute "$out/$name.json" --preset ci --force 2>"$out/$name.log")" || {
    cat "$out/$name.log"; echo "user_plants: $name did not build"; exit 1; }
  "$meadow" inspect "$lib" --json >"$out/$name.inspect.json"
  python3 - "$out/$name.inspect.json" "$name" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
(clump,) = j["clumps"]
m = clump["motion"]; g = m["graph"]
frames = [level["frames"] for level in m["levels"]]
assert g["stronglyConnected"] and g["levelsStronglyConnected"], g
for level, (live, total) in enumerate(zip(g["levelLiveFrames"], frames)):
    assert live >= total / 4, f"level {level} keeps {live} of {total} frames"
adapted = [l for l, (s, loop) in enumerate(zip(g["levelThresholdScale"], g["levelLoopFrames"])) if s != 1 or loop > 0]
said = g["adaptations"]
assert bool(adapted) == bool(said), (adapted, said)
for l in adapted:
    assert any(f"wind level {l}:" in line for line in said), (l, said)
for l, loop in enumerate(g["levelLoopFrames"]):
    assert loop == 0 or frames[l] / 2 < loop <= g["levelLiveFrames"][l], (l, loop, frames[l])
w = m["windResponse"]
assert w["unreached"] == 0, w
print(f"{sys.argv[2]}: live frames {g['levelLiveFrames']} of {frames}, thresholds {g['levelThresholdScale']}, "
      f"loops {g['levelLoopFrames']}, wind response up {w['medianSeconds']['up']:.2f} s down {w['medianSeconds']['down']:.2f} s")
for line in said:
    print("  ", line)
PY
done

# The textured plant's orange tips and blue bases appear in a render; the untextured one has
# neither (it is meadow's leaf green).
for name in painted three_blades; do
  "$meadow" render "$out/$name.json" --preset ci --size 160x120 --out "$out/$name.png" 2>"$out/$name.render.log" || {
    cat "$out/$name.render.log"; exit 1; }
done
python3 - "$out/painted.png" "$out/three_blades.png" <<'PY'
import subprocess, sys
def pixels(path):
    subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-d", "uint8", "-o", path + ".ppm"], check=True)
    data = open(path + ".ppm", "rb").read()
    fields, at = [], 0
    while len(fields) < 4:  # P6, width, height, maximum; then one whitespace byte
        while data[at:at + 1].isspace():
            at += 1
        start = at
        while not data[at:at + 1].isspace():
            at += 1
        fields.append(data[start:at])
    raw = data[at + 1:]
    width, height = int(fields[1]), int(fields[2])
    assert fields[0] == b"P6" and fields[3] == b"255" and len(raw) == width * height * 3, fields
    return [tuple(raw[i:i + 3]) for i in range(0, len(raw), 3)]
def count(px):
    orange = sum(1 for r, g, b in px if r > 60 and r > 1.4 * g and g > 1.3 * b)
    blue = sum(1 for r, g, b in px if b > 50 and b > 1.8 * r and b > 1.3 * g)
    return orange, blue
painted, plain = count(pixels(sys.argv[1])), count(pixels(sys.argv[2]))
print("orange, blue pixels: painted", painted, "untextured", plain)
assert painted[0] > 200 and painted[1] > 200, painted
assert painted[0] > 10 * max(plain[0], 1) and painted[1] > 10 * max(plain[1], 1), (painted, plain)
PY

# Not a plant: a closed solid is refused, naming the file and the reason, and writes nothing.
scene red_cube red_cube.gltf
if "$meadow" precompute "$out/red_cube.json" --preset ci --force --out "$out/red_cube.mlib" 2>"$out/red_cube.log"; then
  echo "user_plants: the closed cube was accepted as a plant"; exit 1
fi
grep -q "red_cube.gltf.*closed solid" "$out/red_cube.log" || { cat "$out/red_cube.log"; echo "user_plants: wrong message"; exit 1; }
test ! -e "$out/red_cube.mlib" || { echo "user_plants: a refused plant left a library"; exit 1; }
echo "user_plants: ok"
