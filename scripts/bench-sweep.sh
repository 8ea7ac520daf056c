#!/usr/bin/env bash
# Sweeps `meadow bench` over field sizes (the default scene's clumps tiled, docs/INTERFACE.md) and
# writes a table (Markdown) and a plot (PNG) of frame time and per-pass GPU time against clump
# count, plus every run's JSON.
#   scripts/bench-sweep.sh [--meadow BIN | --bench CMD] [--scene SCENE] [--size WxH] [--frames F]
#                          [--out DIR] [--preset P] [--far-radius PX] [COUNTS...]
# Defaults: the Release build (scripts/build.sh), 1280x720, 30 frames, out/bench-sweep/ in the
# repository (ignored by git), the full preset, data/scenes/irises.json, counts 10000 30000 100000
# 300000 1000000, bench's default far field (--far-radius PX: bench's option, 0 turns the far field
# off; the table has the far field's two passes when it runs).
# --bench CMD runs CMD SCENE [bench options] instead of `meadow bench`: the bench runner of a
# bundle (scripts/bundle-bench.sh) sweeps with it on a machine without meadow's build.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
meadow="$root/build/engine/meadow"
size=1280x720
frames=30
out="$root/out/bench-sweep"
preset=full
scene="$root/data/scenes/irises.json"
bench=()
bundled=""
counts=()
far=()
while [ $# -gt 0 ]; do
  case "$1" in
    --meadow) meadow="$2"; shift 2 ;;
    --bench) bench=("$2"); bundled=1; shift 2 ;;
    --scene) scene="$2"; shift 2 ;;
    --size) size="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --preset) preset="$2"; shift 2 ;;
    --far-radius) far=(--far-radius "$2"); shift 2 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    -*) echo "bench-sweep: unknown option $1" >&2; exit 2 ;;
    *) counts+=("$1"); shift ;;
  esac
done
[ ${#counts[@]} -gt 0 ] || counts=(10000 30000 100000 300000 1000000)
if [ ${#bench[@]} -eq 0 ]; then
  if [ ! -x "$meadow" ]; then
    bash "$root/scripts/build.sh" "$root/build" -DCMAKE_BUILD_TYPE=Release
  fi
  bench=("$meadow" bench)
fi
# The plot needs matplotlib (Debian: python3-matplotlib, for the system's python3); the table
# does not.
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3
# With --bench (a bundle on another machine) nothing is installed: the table comes regardless.
if [ -z "$bundled" ] && ! "$py" -c "import matplotlib" 2>/dev/null && command -v apt-get >/dev/null &&
   [ "$(id -u)" = 0 ]; then
  apt-get install -y -qq python3-matplotlib >/dev/null || true
fi
mkdir -p "$out"
for n in "${counts[@]}"; do
  echo "bench-sweep: $n clumps at $size, $frames frames" >&2
  "${bench[@]}" "$scene" --preset "$preset" --clumps "$n" --frames "$frames" --size "$size" "${far[@]}" \
    --json "$out/bench-$n.json" > /dev/null
done

"$py" - "$out" "${counts[@]}" <<'EOF'
import json, sys, os
out, counts = sys.argv[1], [int(c) for c in sys.argv[2:]]
runs = [json.load(open(os.path.join(out, f"bench-{n}.json"))) for n in counts]
passes = ["animate", "cull", "light", "draw", "tonemap"]
if any("farSplat" in r["gpuMs"] for r in runs):
    passes[4:4] = ["farSplat"]
lines = [f"Device: {runs[0]['device']} ({runs[0]['vulkanDriver']}), {runs[0]['width']}x{runs[0]['height']}, "
         f"{runs[0]['frames']} frames per run, median.", "",
         "| clumps | frame ms | fps | " + " | ".join(f"{p} ms" for p in passes) +
         " | triangles | visible | CPU ms | bytes/frame |",
         "|" + "---|" * (7 + len(passes))]
for r in runs:
    g = r["gpuMs"]
    lines.append(f"| {r['clumps']:,} | {r['frameMs']['median']:.1f} | {1000 / r['frameMs']['median']:.1f} | " +
                 " | ".join(f"{g.get(p, 0):.2f}" for p in passes) +
                 f" | {r['trianglesPerFrame']:,} | {r['visibleInstances']:,} | {r['cpuMsPerFrame']:.3f} | "
                 f"{r['uploadBytesPerFrame']} |")
table = "\n".join(lines) + "\n"
open(os.path.join(out, "sweep.md"), "w").write(table)
print(table)
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("bench-sweep: no matplotlib (python3-matplotlib); table only", file=sys.stderr)
    sys.exit(0)
fig, ax = plt.subplots(figsize=(7, 4.5))
x = [r["clumps"] for r in runs]
ax.plot(x, [r["frameMs"]["median"] for r in runs], "k-o", label="frame (wall)")
for p in passes:
    ax.plot(x, [max(r["gpuMs"].get(p, 0), 1e-3) for r in runs], "--.", label=p)
ax.set_xscale("log"); ax.set_yscale("log")
ax.set_xlabel("clumps"); ax.set_ylabel("ms (median)")
ax.set_title(f"meadow bench: {runs[0]['device']}, {runs[0]['width']}x{runs[0]['height']}")
ax.grid(True, which="both", alpha=0.3); ax.legend(fontsize=8)
fig.tight_layout(); fig.savefig(os.path.join(out, "sweep.png"), dpi=110)
print(f"bench-sweep: {os.path.join(out, 'sweep.md')} and sweep.png", file=sys.stderr)
EOF
