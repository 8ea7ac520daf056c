#!/usr/bin/env bash
# --lod-tolerance: the switch radii scale with the screen-space error it allows, and a larger one
# draws fewer triangles. The ci field from its own camera at 640x360, benched at the default 0.3 px
# and at 0.9 px: every radius 3 times the default's, fewer triangles, and fewer instances at LOD 0
# and 1 (the coarser LODs take them). The far field is on by default, at 28 px at 0.3 px and scaled
# with the tolerance (84 px at 0.9), so it takes more clumps; `--far-radius 0` turns it off.
#   lod_tolerance.sh MEADOW SCENE OUTDIR
set -euo pipefail
meadow="$1"; scene="$2"; out="$3"
mkdir -p "$out"
"$meadow" bench "$scene" --preset ci --size 640x360 --frames 2 --json "$out/lod-default.json" >/dev/null
"$meadow" bench "$scene" --preset ci --size 640x360 --frames 2 --lod-tolerance 0.9 --json "$out/lod-coarse.json" >/dev/null
"$meadow" bench "$scene" --preset ci --size 640x360 --frames 2 --far-radius 0 --json "$out/lod-nofar.json" >/dev/null
python3 - "$out/lod-default.json" "$out/lod-coarse.json" "$out/lod-nofar.json" <<'PY'
import json, sys
a, b, c = (json.load(open(p)) for p in sys.argv[1:4])
# Triangles drawn: the graphics pipeline's and the near raster's (on by default).
for j in (a, b, c):
    j["trianglesPerFrame"] += j["nearRasterTriangles"]
assert a["nearRasterTriangles"] > 0, a
assert abs(a["farRadius"] - 28.0) < 1e-4 and abs(b["farRadius"] - 84.0) < 1e-3, (a["farRadius"], b["farRadius"])
assert 0 < a["instancesFar"] < b["instancesFar"], (a["instancesFar"], b["instancesFar"])
assert c["farRadius"] == 0 and c["instancesFar"] == 0 and c["splatsPerFrame"] == 0, c
assert c["trianglesPerFrame"] > a["trianglesPerFrame"], (c["trianglesPerFrame"], a["trianglesPerFrame"])
ra, rb = a["lodSwitchRadii"], b["lodSwitchRadii"]
assert len(ra) == 4 and len(rb) == 4, (ra, rb)
assert all(x > y > 0 for x, y in zip(ra, ra[1:])), ra
for x, y in zip(ra, rb):
    assert abs(y / x - 3.0) < 1e-4, (ra, rb)
assert b["trianglesPerFrame"] < a["trianglesPerFrame"], (a["trianglesPerFrame"], b["trianglesPerFrame"])
fine = lambda j: j["instancesPerLod"][0] + j["instancesPerLod"][1]
assert fine(b) < fine(a), (a["instancesPerLod"], b["instancesPerLod"])
print("switch radii", ["%.1f" % x for x in ra], "->", ["%.1f" % x for x in rb],
      "; triangles", a["trianglesPerFrame"], "->", b["trianglesPerFrame"],
      "; instances per LOD", a["instancesPerLod"], "->", b["instancesPerLod"],
      "; far radius", a["farRadius"], "->", b["farRadius"], "; far instances", a["instancesFar"], "->",
      b["instancesFar"], "(none with --far-radius 0)")
PY
