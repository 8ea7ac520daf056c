#!/usr/bin/env bash
# A stale or corrupt library in the cache is rebuilt, never trusted, by `meadow precompute` and by
# `meadow render` (which builds what it lacks), and the rebuild writes the same bytes as before.
#   cache_rebuild.sh MEADOW SCENE WORK_DIR
set -euo pipefail
meadow="$1"; scene="$2"; work="$3"
export MEADOW_CACHE_DIR="$work/cache"
rm -rf "$work"; mkdir -p "$MEADOW_CACHE_DIR"
fail() { echo "FAIL: $1"; exit 1; }
# Under the sanitizers (scripts/sanitize.sh), rendering loads the Vulkan driver, which is not built
# with them and leaves a few hundred bytes at exit in a module already unloaded (LeakSanitizer
# cannot name it, so no suppression can): leaks are not looked for in the render commands.
render_env=(env "ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0")

lib="$("$meadow" precompute "$scene" --preset ci 2>/dev/null)"
cp "$lib" "$work/good.mlib"

# Flip one byte in the middle of the file: a section's checksum no longer matches.
spoil() {
  python3 - "$lib" <<'PY'
import sys
path = sys.argv[1]
data = bytearray(open(path, "rb").read())
data[len(data) // 2] ^= 0x01
open(path, "wb").write(data)
PY
}

spoil
cmp -s "$lib" "$work/good.mlib" && fail "the library was not spoiled"
"$meadow" precompute "$scene" --preset ci >/dev/null 2>"$work/precompute.err" || fail "precompute failed: $(cat "$work/precompute.err")"
grep -q "rebuilding: library .*checksum mismatch" "$work/precompute.err" || fail "precompute did not say it rebuilds: $(cat "$work/precompute.err")"
cmp "$lib" "$work/good.mlib" || fail "precompute's rebuild differs from the first build"

spoil
"${render_env[@]}" "$meadow" render "$scene" --preset ci --size 32x32 --out "$work/frame.png" 2>"$work/render.err" || fail "render failed: $(cat "$work/render.err")"
grep -q "cached library is unusable, rebuilding" "$work/render.err" || fail "render did not say it rebuilds: $(cat "$work/render.err")"
cmp "$lib" "$work/good.mlib" || fail "render's rebuild differs from the first build"
[ -s "$work/frame.png" ] || fail "render wrote no image"

# An older format version at the cache path: stale, rebuilt.
python3 - "$lib" <<'PY'
import struct, sys
path = sys.argv[1]
data = bytearray(open(path, "rb").read())
struct.pack_into("<I", data, 8, struct.unpack_from("<I", data, 8)[0] - 1)
open(path, "wb").write(data)
PY
"${render_env[@]}" "$meadow" render "$scene" --preset ci --size 32x32 --out "$work/frame2.png" 2>"$work/render2.err" || fail "render failed: $(cat "$work/render2.err")"
grep -q "is stale or corrupt, rebuilding" "$work/render2.err" || fail "render did not rebuild a stale library: $(cat "$work/render2.err")"
cmp "$lib" "$work/good.mlib" || fail "the rebuild of a stale library differs from the first build"
[ "$(ls "$MEADOW_CACHE_DIR")" = "$(basename "$lib")" ] || fail "the cache holds more than the library: $(ls "$MEADOW_CACHE_DIR")"
echo "PASS"
