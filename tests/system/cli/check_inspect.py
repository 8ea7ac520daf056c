"""Checks the inspect JSON of the default scene's ci library (precompute_inspect.sh): a field of
clumps and rocks without overlaps, Wang tiles denser than Poisson discs, four clumps whose motion
graphs are strongly connected at every wind level, whose LOD 0 plays its motion within 1 %, and
whose five LODs have ever fewer triangles."""
import json
import sys

j = json.load(open(sys.argv[1]))
f = j["field"]
t = j["tiles"]
assert f["clumps"] > 400 and f["rocks"] > 0, f
assert f["overlapViolations3d"] == 0 and t["overlapViolations"] == 0, (f, t)
assert t["densityVsPoissonDisc"] >= 1.5 and t["count"] == 16, t
assert len(j["clumps"]) == 4, len(j["clumps"])
for c in j["clumps"]:
    graph = c["motion"]["graph"]
    assert graph["stronglyConnected"] and graph["levelsStronglyConnected"], (c["name"], graph)
    assert c["motion"]["pcaRelError"][c["lods"][0]["motionModes"]] <= 0.01, c["name"]
    lods = c["lods"]
    assert len(lods) == 5 and all(lods[i]["triangles"] > lods[i + 1]["triangles"] for i in range(4)), c["name"]
