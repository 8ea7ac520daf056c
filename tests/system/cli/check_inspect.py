"""Checks the inspect JSON of the default scene's ci library (precompute_inspect.sh): a field of
clumps and rocks without overlaps, Wang tiles denser than Poisson discs, four clumps whose motion
graphs are strongly connected at every wind level, whose LOD 0 plays its motion within 1 %, and
whose five LODs have ever fewer triangles; every clump and rock with its far-field samples."""
import json
import sys

j = json.load(open(sys.argv[1]))
f = j["field"]
t = j["tiles"]
assert f["clumps"] > 400 and f["rocks"] > 0, f
assert f["overlapViolations3d"] == 0 and t["overlapViolations"] == 0, (f, t)
# The scan-line tiling draws from Cohen et al.'s 8 tiles; the figures are those of the tiles used.
assert 1 <= f["wangTiles"] <= 8 and t["count"] == f["wangTiles"] == len(t["clumpsPerTile"]), (f, t)
assert t["completeSet"]["count"] == 16 and len(t["completeSet"]["clumpsPerTile"]) == 16, t
assert t["densityVsPoissonDisc"] >= 1.5 and t["completeSet"]["densityVsPoissonDisc"] >= 1.5, t
assert len(t["sweptFrames"]) == len(t["simulatedFrames"]) == 4, t
assert all(0 < s <= n for s, n in zip(t["sweptFrames"], t["simulatedFrames"])), t
assert len(j["clumps"]) == 4, len(j["clumps"])
for c in j["clumps"]:
    graph = c["motion"]["graph"]
    assert graph["stronglyConnected"] and graph["levelsStronglyConnected"], (c["name"], graph)
    assert c["motion"]["pcaRelError"][c["lods"][0]["motionModes"]] <= 0.01, c["name"]
    wind = c["motion"]["windResponse"]
    assert wind["walks"] == 1000 and wind["unreached"] == 0, (c["name"], wind)
    assert 0 < wind["medianSeconds"]["up"] <= wind["p95Seconds"]["up"] < 100, (c["name"], wind)
    assert 0 < wind["medianSeconds"]["down"] <= wind["p95Seconds"]["down"] < 100, (c["name"], wind)
    lods = c["lods"]
    assert len(lods) == 5 and all(lods[i]["triangles"] > lods[i + 1]["triangles"] for i in range(4)), c["name"]
    # Area in the mean pose against LOD 0's: LOD 0 is itself; the coarsest LOD loses thin parts' tips.
    assert lods[0]["areaFraction"] == 1.0 and 0.1 < lods[4]["areaFraction"] < 1.0, (c["name"], lods)
    # The simplifier's area term keeps LODs 1-3's surface (SimplifyOptions::areaWeight): in this
    # library they keep 0.91-0.92, 0.64-0.74 and 0.49-0.51 of it; without the term 0.85-0.86,
    # 0.52-0.60 and 0.35-0.38, below every floor here.
    floors = [0.88, 0.62, 0.45]
    assert all(lods[i]["areaFraction"] >= floors[i - 1] for i in (1, 2, 3)), (c["name"], [l["areaFraction"] for l in lods])
# The far field's surface samples: the ci preset's 1024 per clump and rock, over a positive area,
# with their coverage gains (5 sizes of 4 elevations, 4 bytes each): positive, and for rocks (closed
# solids, whose independent splats leave holes) above 1 once they span pixels.
for far in [c["far"] for c in j["clumps"]] + [r["far"] for r in j["rocks"]]:
    assert far["samples"] == 1024 and far["area"] > 0 and far["bytes"] == 8 + 4 * 20 + 32 * 1024, far
    # Self-occlusion (far_splat.h): from every elevation some samples are in sight, and from the
    # side some are hidden by their own clump or rock (its inside, its far side). From above, a
    # rock's samples nearly all face some of the cell: 0.96 in this library.
    share = far["visibleShare"]
    assert len(share) == 4 and all(0.05 < v <= 1.0 for v in share) and share[0] < 0.9, far
    gain = far["coverageGain"]
    assert len(gain) == 5 and all(len(row) == 4 and all(0 < g < 16 for g in row) for row in gain), far
for rock in j["rocks"]:
    assert all(g > 1.2 for row in rock["far"]["coverageGain"][2:] for g in row), rock
assert len(j["rocks"]) == f["rockVariants"], j["rocks"]
