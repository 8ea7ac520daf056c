#!/usr/bin/env bash
# Runs `meadow bench` from a fixed set of views over and across the default field, each ROUNDS
# times, and writes a table (Markdown) of the frame time and the per-pass GPU time per view (the
# median of the rounds' medians), plus every run's JSON: the "any view over or across the field"
# of the 10 fps target (docs/BENCHMARKS.md).
#   scripts/bench-views.sh [--meadow BIN] [--scene SCENE] [--preset P] [--size WxH] [--frames F]
#                          [--rounds R] [--out DIR] [--args OPTS] [--versus BIN] [--versus-args OPTS]
#                          [VIEWS...]
# Defaults: the Release build (scripts/build.sh), the full preset, 1280x720, 30 frames, 1 round,
# out/bench-views/ in the repository (ignored by git), data/scenes/irises.json, every view below.
# VIEWS names some. --args adds bench options to every run (one string, e.g. "--far-radius 36").
# A comparison: --versus BIN (another meadow) and/or --versus-args OPTS (options added to --args'
# for its runs, none of them the same; alone, the same meadow with them) run a second series
# beside the first, the two in turn in each round and view (the order swapped every other round),
# so that a host whose load drifts moves both alike. The table then gives both medians, the median
# of the rounds' changes and in how many rounds the second was faster; per pass, the first's
# median / the second's.
# The views (eye x,y,z then target x,y,z, metres; the field is a 105 m square about the origin):
#   default  the scene's camera          low     across the field from outside it, 1.2 m up
#   high     high oblique, over a corner inside  among the irises at eye height
#   diag     along the diagonal, 2 m up  down6   6 m up, looking down into the field
#   side     from outside one side       top     40 m straight down on the middle
#   aerial   far and high over a corner  walk    a walk at eye height, looking across
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
meadow="$root/build/engine/meadow"
meadow_given=""
scene="$root/data/scenes/irises.json"
size=1280x720
frames=30
rounds=1
preset=full
out="$root/out/bench-views"
args=""
versus=""
versus_args=""
compare=""
declare -A cameras=(
  [default]="" [low]="-30,1.2,-30,0,0.4,0" [high]="-22,16,-22,4,0,4" [inside]="0,1.7,0,30,0.5,30"
  [diag]="-60,2,-60,0,0,0" [down6]="0,6,0,10,0,10" [side]="0,1.5,-60,0,0.5,0" [top]="0,40,0.1,0,0,0"
  [aerial]="-80,30,-80,0,0,0" [walk]="10,1.7,-20,-20,1.2,20")
order=(default low high inside diag down6 side top aerial walk)
views=()
while [ $# -gt 0 ]; do
  case "$1" in
    --meadow|--scene|--preset|--size|--frames|--rounds|--out|--args|--versus|--versus-args)
      [ $# -ge 2 ] || { echo "bench-views: $1 needs a value" >&2; exit 2; } ;;
  esac
  case "$1" in
    --meadow) meadow="$2"; meadow_given=1; shift 2 ;;
    --args) args="$2"; shift 2 ;;
    --versus) versus="$2"; compare=1; shift 2 ;;
    --versus-args) versus_args="$2"; compare=1; shift 2 ;;
    --scene) scene="$2"; shift 2 ;;
    --preset) preset="$2"; shift 2 ;;
    --size) size="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --rounds) rounds="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) sed -n '2,23p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "bench-views: unknown option $1" >&2; exit 2 ;;
    *)
      if [ -z "${cameras[$1]+set}" ]; then
        echo "bench-views: unknown view '$1' (views: ${order[*]})" >&2; exit 2
      fi
      views+=("$1"); shift ;;
  esac
done
[[ "$rounds" =~ ^[1-9][0-9]*$ ]] || { echo "bench-views: --rounds needs a whole number from 1, not '$rounds'" >&2; exit 2; }
[ ${#views[@]} -gt 0 ] || views=("${order[@]}")
if [ ! -x "$meadow" ]; then
  if [ -n "$meadow_given" ]; then
    echo "bench-views: --meadow $meadow is not an executable" >&2; exit 2
  fi
  bash "$root/scripts/build.sh" "$root/build" -DCMAKE_BUILD_TYPE=Release
fi
if [ -n "$compare" ]; then
  [ -n "$versus" ] || versus="$meadow"
  [ -x "$versus" ] || { echo "bench-views: --versus $versus is not an executable" >&2; exit 2; }
fi
read -r -a extra <<< "$args"
read -r -a versus_extra <<< "$versus_args"
mkdir -p "$out"
# One run: which series (first or versus), the view, the round.
run() {
  local bin="$meadow" opts=("${extra[@]}") tail=""
  if [ "$1" = versus ]; then bin="$versus"; opts+=("${versus_extra[@]}"); tail="-versus"; fi
  local cam=(); [ -n "${cameras[$2]}" ] && cam=(--camera "${cameras[$2]}")
  "$bin" bench "$scene" --preset "$preset" --frames "$frames" --size "$size" "${cam[@]}" "${opts[@]}" \
    --json "$out/bench-$2-$3$tail.json" > /dev/null
}
# Rounds outside, views inside: a machine whose speed drifts moves every view alike.
for ((r = 1; r <= rounds; ++r)); do
  for v in "${views[@]}"; do
    echo "bench-views: round $r of $rounds, view $v at $size, $frames frames" >&2
    if [ -z "$compare" ]; then
      run first "$v" "$r"
    elif ((r % 2)); then
      run first "$v" "$r"; run versus "$v" "$r"
    else
      run versus "$v" "$r"; run first "$v" "$r"
    fi
  done
done

python3 - "$out" "$rounds" "$compare" "${views[@]}" <<'EOF'
import json, os, statistics, sys
out, rounds, compare, views = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "1", sys.argv[4:]
load = lambda v, r, tail: json.load(open(os.path.join(out, f"bench-{v}-{r}{tail}.json")))
runs = {v: [load(v, r, "") for r in range(1, rounds + 1)] for v in views}
others = {v: [load(v, r, "-versus") for r in range(1, rounds + 1)] for v in views} if compare else {}
first = runs[views[0]][0]
# Every pass the runs timed, as the bench JSON names them ("far" repeats "farSplat"), in either series.
passes = [p for p in first["gpuMs"] if p not in ("total", "far")]
if compare:
    passes += [p for p in others[views[0]][0]["gpuMs"] if p not in ("total", "far") and p not in passes]
med = statistics.median
frameOf = lambda rs: med([r["frameMs"]["median"] for r in rs])
passOf = lambda rs, p: med([r["gpuMs"].get(p, 0) for r in rs])
frame = {v: frameOf(rs) for v, rs in runs.items()}
head = (f"Device: {first['device']} ({first['vulkanDriver']}), {first['width']}x{first['height']}, "
        f"{first['frames']} frames per run, {rounds} round(s); the median of the rounds' medians")
if not compare:
    lines = [head + " (rounds: each round's frame median).", "",
             "| view | frame ms | fps | rounds | p95 ms | " + " | ".join(f"{p} ms" for p in passes) + " |",
             "|" + "---|" * (5 + len(passes))]
    for v in views:
        rs = runs[v]
        lines.append(f"| {v} | {frame[v]:.1f} | {1000 / frame[v]:.1f} | " +
                     ", ".join(f"{r['frameMs']['median']:.1f}" for r in rs) +
                     f" | {med([r['frameMs']['p95'] for r in rs]):.1f} | " +
                     " | ".join(f"{passOf(rs, p):.1f}" for p in passes) + " |")
    worst = max(views, key=frame.get)
    lines += ["", f"Slowest view: {worst}, {frame[worst]:.1f} ms."]
else:
    lines = [head + ", the first series against the versus series, run in turn (change: the median of "
             "the rounds' (versus - first) / first; faster: the rounds in which versus took less).", "",
             "| view | frame ms | versus ms | change | versus faster | " + " | ".join(f"{p} ms" for p in passes) + " |",
             "|" + "---|" * (5 + len(passes))]
    for v in views:
        a, b = runs[v], others[v]
        changes = [(y["frameMs"]["median"] - x["frameMs"]["median"]) / x["frameMs"]["median"] for x, y in zip(a, b)]
        faster = sum(y["frameMs"]["median"] < x["frameMs"]["median"] for x, y in zip(a, b))
        lines.append(f"| {v} | {frame[v]:.1f} | {frameOf(b):.1f} | {100 * med(changes):+.1f} % | {faster} of {rounds} | " +
                     " | ".join(f"{passOf(a, p):.1f} / {passOf(b, p):.1f}" for p in passes) + " |")
table = "\n".join(lines) + "\n"
open(os.path.join(out, "views.md"), "w").write(table)
print(table)
EOF
