#!/usr/bin/env bash
# scripts/bench-views.sh, the benchmark of the 10 fps target's views, on the ci field: it runs
# the views it is given for every round, writes their table (a row per view, each round's median)
# and every run's JSON; it compares two series run in turn (--versus, --versus-args); it refuses a
# view it does not know, a --meadow or --versus that is not there and an option without its value,
# naming them, without running or writing anything.
#   bench_views.sh MEADOW SCENE OUT_DIR      (environment: the tests' lavapipe and cache)
set -euo pipefail
root="$(cd "$(dirname "$0")/../../.." && pwd)"
meadow="$1"; scene="$2"; out="$3"
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$out"; mkdir -p "$out"

bash "$root/scripts/bench-views.sh" --meadow "$meadow" --scene "$scene" --preset ci --size 160x90 --frames 2 \
  --rounds 2 --out "$out/views" default top > "$out/table.txt"
cat "$out/table.txt"
for v in default top; do
  for r in 1 2; do
    python3 -c "import json, sys; d = json.load(open(sys.argv[1])); assert d['frames'] == 2 and d['width'] == 160, d" \
      "$out/views/bench-$v-$r.json" || fail "bench-$v-$r.json is not a 2-frame 160x90 bench run"
  done
  # A row per view: its name, the median of the rounds, fps, then the two rounds' medians.
  grep -Eq "^\| $v \| [0-9.]+ \| [0-9.]+ \| [0-9.]+, [0-9.]+ \|" "$out/views/views.md" || fail "no row for view $v"
done
[ "$(grep -c '^| [a-z0-9]* | [0-9]' "$out/views/views.md")" = 2 ] || fail "the table should have exactly two rows"
grep -q "^| top |" "$out/table.txt" || fail "the table was not printed"
# The top view looks straight down from 40 m: far fewer visible instances than the scene's camera.
python3 - "$out/views" <<'PY' || fail "the views did not see different things"
import json, sys
d = json.load(open(f"{sys.argv[1]}/bench-default-1.json")); t = json.load(open(f"{sys.argv[1]}/bench-top-1.json"))
assert d["visibleInstances"] != t["visibleInstances"], (d["visibleInstances"], t["visibleInstances"])
PY

# A comparison: --args reach both series, --versus-args only the second, which runs beside the
# first in every round; the table gives both series' medians and the rounds' change.
bash "$root/scripts/bench-views.sh" --meadow "$meadow" --scene "$scene" --preset ci --size 160x90 --frames 2 \
  --rounds 2 --out "$out/versus" --args "--lod-tolerance 0.4" --versus "$meadow" --versus-args "--far-radius 0" \
  default > "$out/versus.txt"
cat "$out/versus.txt"
python3 - "$out/versus" <<'PY' || fail "the comparison's runs did not take their options"
import json, sys
for r in (1, 2):
    a = json.load(open(f"{sys.argv[1]}/bench-default-{r}.json"))
    b = json.load(open(f"{sys.argv[1]}/bench-default-{r}-versus.json"))
    # The far radius scales with the tolerance (28 px at 0.3 px); the versus series has none.
    assert abs(a["farRadius"] - 28.0 * 0.4 / 0.3) < 0.01 and b["farRadius"] == 0.0, (a["farRadius"], b["farRadius"])
    assert a["lodSwitchRadii"] == b["lodSwitchRadii"], (a["lodSwitchRadii"], b["lodSwitchRadii"])
    assert a["instancesFar"] > 0 and b["instancesFar"] == 0, (a["instancesFar"], b["instancesFar"])
PY
grep -Eq "^\| default \| [0-9.]+ \| [0-9.]+ \| [-+][0-9.]+ % \| [0-2] of 2 \| [0-9.]+ / [0-9.]+ \|" "$out/versus/views.md" ||
  fail "no comparison row for the default view"
if bash "$root/scripts/bench-views.sh" --meadow "$meadow" --versus "$out/no-such-meadow" --out "$out/bad" default \
  2> "$out/bad.txt"; then
  fail "a missing --versus was accepted"
fi
grep -q -- "--versus .*no-such-meadow is not an executable" "$out/bad.txt" ||
  fail "the message does not name the missing versus binary: $(cat "$out/bad.txt")"
[ ! -e "$out/bad" ] || fail "a missing --versus still wrote $out/bad"

if bash "$root/scripts/bench-views.sh" --meadow "$meadow" --out "$out/bad" default nowhere 2> "$out/bad.txt"; then
  fail "an unknown view was accepted"
fi
grep -q "unknown view 'nowhere'" "$out/bad.txt" || fail "the message does not name the unknown view: $(cat "$out/bad.txt")"
[ ! -e "$out/bad" ] || fail "an unknown view still wrote $out/bad"
if bash "$root/scripts/bench-views.sh" --meadow "$out/no-such-meadow" --out "$out/bad" default 2> "$out/bad.txt"; then
  fail "a missing --meadow was accepted"
fi
grep -q "no-such-meadow is not an executable" "$out/bad.txt" || fail "the message does not name the missing binary: $(cat "$out/bad.txt")"
[ ! -e "$out/bad" ] || fail "a missing --meadow still wrote $out/bad"
if bash "$root/scripts/bench-views.sh" --meadow "$meadow" --out "$out/bad" --rounds 2> "$out/bad.txt"; then
  fail "--rounds without a value was accepted"
fi
grep -q -- "--rounds needs a value" "$out/bad.txt" || fail "the message does not name the option: $(cat "$out/bad.txt")"
[ ! -e "$out/bad" ] || fail "an option without its value still wrote $out/bad"
echo "bench-views: ok"
