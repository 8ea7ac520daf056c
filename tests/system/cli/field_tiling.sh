#!/usr/bin/env bash
# The scene key field.tiling chooses how tiles are laid: the micro scene on 6 x 6 tiles, laid by
# the scan-line tiling (Cohen et al.'s 8 tiles) and by the hash tiling (all 16), each through
# precompute and inspect. Inspect names the tiling, and the field uses at most 8 tiles with the
# first and more than 8 with the second (36 hashed tiles miss one of 16 with odds below 1 in 40).
#   field_tiling.sh MEADOW MICRO_SCENE OUTDIR
set -euo pipefail
meadow="$1"; micro="$2"; out="$3"
mkdir -p "$out"
for tiling in scanline hash; do
  python3 - "$micro" "$out/tiling-$tiling.json" "$tiling" <<'PY'
import json, os, sys
scene = json.load(open(sys.argv[1]))
scene["name"] = "tiling_" + sys.argv[3]
scene["field"].update({"tilesX": 6, "tilesY": 6, "tiling": sys.argv[3]})
scene["plants"]["gltf"] = os.path.join(os.path.dirname(os.path.abspath(sys.argv[1])), scene["plants"]["gltf"])
json.dump(scene, open(sys.argv[2], "w"))
PY
  "$meadow" precompute "$out/tiling-$tiling.json" --preset ci --force --out "$out/tiling-$tiling.mlib" 2>/dev/null
  "$meadow" inspect "$out/tiling-$tiling.mlib" --json >"$out/tiling-$tiling.inspect.json"
  python3 - "$out/tiling-$tiling.inspect.json" "$tiling" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
f, t = j["field"], j["tiles"]
assert f["tiling"] == sys.argv[2], f
assert t["count"] == f["wangTiles"] and t["completeSet"]["count"] == 16, t
if sys.argv[2] == "scanline":
    assert f["wangTiles"] <= 8, f
else:
    assert f["wangTiles"] > 8, f
print(sys.argv[2], "tiling:", f["wangTiles"], "tiles", t["indices"])
PY
done
