#!/usr/bin/env python3
"""Checks the log of the scripted walkthrough (tests/data/walkthrough/walkthrough.txt) against
what the script asks for, and the camera path it recorded.
    window_check.py LOG RECORDED_PATH
The numbers here are the walkthrough's: 5 m/s, 1/30 s per scripted frame, 0.003 rad per pixel of
mouse drag, the eye 1.7 m above the ground when walking."""
import json
import math
import re
import sys

SPEED, STEP, LOOK, EYE_HEIGHT = 5.0, 1.0 / 30.0, 0.003, 1.7
# The log prints 4 decimals of position and 5 of angles.
POSITION_TOL, ANGLE_TOL = 2e-4, 2e-5

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def near(a, b, tol, what):
    check(abs(a - b) <= tol, f"{what}: {a} is not {b} (within {tol})")


def near3(a, b, tol, what):
    for i in range(3):
        near(a[i], b[i], tol, f"{what}[{'xyz'[i]}]")


log = open(sys.argv[1], encoding="utf-8").read()
states = {}
for line in log.splitlines():
    m = re.search(r"meadow: state (.*)", line)
    if not m:
        continue
    fields = dict(kv.split("=", 1) for kv in m.group(1).split())
    s = {k: v for k, v in fields.items()}
    s["eye"] = [float(v) for v in fields["eye"].split(",")]
    for key in ("yaw", "pitch", "ground", "speed", "wind", "hours"):
        s[key] = float(fields[key])
    for key in ("walk", "lod", "freeze", "vsync", "fullscreen", "playing"):
        s[key] = int(fields[key])
    states[int(fields["frame"])] = s

expected_frames = [0, 31, 34, 51, 59, 62, 66, 70, 88]
missing = [f for f in expected_frames if f not in states]
if missing:
    print(f"FAIL: no 'meadow: state' line for frames {missing}")
    sys.exit(1)

# Frame 0: the --camera pose, eye (-3, 2.2, -17) looking at (2, 0.2, 0).
s0 = states[0]
d = [5.0, -2.0, 17.0]
near3(s0["eye"], [-3.0, 2.2, -17.0], POSITION_TOL, "start eye")
near(s0["yaw"], math.atan2(d[0], d[2]), ANGLE_TOL, "start yaw")
near(s0["pitch"], math.asin(d[1] / math.sqrt(sum(c * c for c in d))), ANGLE_TOL, "start pitch")
check(s0["window"] == "400x240" and s0["vsync"] == 1 and s0["walk"] == 0, "start: 400x240, vsync on, flying")


def forward(yaw, pitch):
    return [math.sin(yaw) * math.cos(pitch), math.sin(pitch), math.cos(yaw) * math.cos(pitch)]


# W held 30 frames: 5 m along the view.
f = forward(s0["yaw"], s0["pitch"])
want = [s0["eye"][i] + 30 * STEP * SPEED * f[i] for i in range(3)]
near3(states[31]["eye"], want, 1e-3, "after W")

# The right drag of (100, -40) pixels: yaw -0.3, pitch +0.12; the eye stays.
near(states[34]["yaw"], states[31]["yaw"] - 100 * LOOK, ANGLE_TOL, "yaw after the drag")
near(states[34]["pitch"], states[31]["pitch"] + 40 * LOOK, ANGLE_TOL, "pitch after the drag")
near3(states[34]["eye"], states[31]["eye"], POSITION_TOL, "eye after the drag")

# Walking 15 frames: 2.5 m on the level along the yaw, the eye 1.7 m above the ground.
s = states[51]
yaw = states[34]["yaw"]
check(s["walk"] == 1, "walking at frame 51")
near(s["eye"][0], states[34]["eye"][0] + 15 * STEP * SPEED * math.sin(yaw), 1e-3, "walk x")
near(s["eye"][2], states[34]["eye"][2] + 15 * STEP * SPEED * math.cos(yaw), 1e-3, "walk z")
near(s["eye"][1] - s["ground"], EYE_HEIGHT, 1e-3, "eye height above the ground")

# The resize, then vsync, wind, time of day, LOD colours, freeze.
check(states[59]["window"] == "320x200" and states[59]["walk"] == 0, "320x200 and flying at frame 59")
s = states[62]
check(s["vsync"] == 0, "vsync off at frame 62")
near(s["wind"], states[59]["wind"] + 0.25, 1e-3, "wind after ]")
near(s["hours"], (states[59]["hours"] + 0.5) % 24.0, 1e-3, "hours after .")
check(s["lod"] == 1 and s["freeze"] == 1, "LOD colours and freeze culling on at frame 62")
check(states[66]["fullscreen"] == 1 and states[66]["window"] == "1024x768", "fullscreen 1024x768 at frame 66")
check(states[70]["fullscreen"] == 0 and states[70]["window"] == "320x200", "back to 320x200 at frame 70")

# The camera path (tests/data/walkthrough/line.json) 16 frames in: 6 m in 2 s along +x.
s = states[88]
t = 16 * STEP
check(s["playing"] == 1, "the path plays at frame 88")
near3(s["eye"], [-6.0 + 3.0 * t, 2.5, -12.0], 1e-3, "eye on the path")
target = [0.0 + 3.0 * t, 0.3, 0.0]
d = [target[i] - s["eye"][i] for i in range(3)]
near(s["yaw"], math.atan2(d[0], d[2]), 1e-4, "yaw on the path")

# The recorded path: keyframes every 0.2 s from R to R, ending where the camera was.
path = json.load(open(sys.argv[2], encoding="utf-8"))
keys = path["keyframes"]
times = [k["time"] for k in keys]
check(path.get("version") == 1, "recorded path version 1")
check(len(keys) >= 4, f"recorded path has {len(keys)} keyframes")
check(all(b > a for a, b in zip(times, times[1:])), f"recorded times increase: {times}")
near(times[0], 0.0, 1e-9, "first recorded time")
near(times[-1], 17 * STEP, 1e-6, "last recorded time (frames 72 to 88)")
near3(keys[-1]["eye"], states[88]["eye"], POSITION_TOL, "last recorded eye")

for what in (
    "window minimised; rendering paused",
    "window restored; rendering resumed",
    "vsync off",
    "fullscreen on",
    "fullscreen off",
    "camera path playing",
    "view showed 91 frames; window 320x200 at exit",
    "validation layer on (synchronization validation included): 0 messages",
):
    check(what in log, f"the log says '{what}'")

# The far field is on by default: the statistics line every 2 s counts the instances it drew.
far_counts = [int(m.group(1)) for m in re.finditer(r"instances visible, (\d+) in the far field", log)]
check(far_counts and max(far_counts) > 0, f"the stats lines count instances in the far field (got {far_counts})")

if failures:
    print("FAIL:\n  " + "\n  ".join(failures))
    sys.exit(1)
print(f"window_check: {len(states)} states as scripted, recorded path of {len(keys)} keyframes")
