#!/usr/bin/env bash
# The bench runner and its bundle (scripts/bundle-bench.sh):
#   1. meadow-bench links only the shared libraries it is meant to (no window, image or ray-tracing
#      library: those are what made meadow too big to carry to a GPU machine);
#   2. the bundle, unpacked from its .tar.gz and run with an empty environment (no
#      LD_LIBRARY_PATH, no cache), benchmarks the ci field with what it carries;
#   3. its figures other than times are those of `meadow bench` on the same field, and so is its
#      last frame (--frame-rgba): WxH raw RGBA pixels, the same bytes, a picture (not one colour).
#   bench_bundle.sh BUILD_DIR OUT_DIR      (environment: the tests' lavapipe and cache)
set -euo pipefail
root="$(cd "$(dirname "$0")/../../.." && pwd)"
build="$1"; out="$2"
fail() { echo "FAIL: $*"; exit 1; }

needed="$(readelf -d "$build/engine/meadow-bench" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | sort | tr '\n' ' ')"
echo "meadow-bench needs: $needed"
for lib in $needed; do
  case "$lib" in
    libvulkan.so.1|libtbb.so.*|libstdc++.so.*|libgcc_s.so.*|libm.so.*|libc.so.*) ;;
    *) fail "meadow-bench links $lib, which the bundle should not need" ;;
  esac
done

rm -rf "$out"; mkdir -p "$out"
tarball="$(bash "$root/scripts/bundle-bench.sh" --preset ci --no-build --build-dir "$build" --out "$out/make")"
mkdir -p "$out/unpacked"
tar -C "$out/unpacked" -xzf "$tarball"
bundle="$out/unpacked/meadow-bench-bundle"
[ -x "$bundle/run.sh" ] || fail "the bundle has no run.sh"
[ -z "$(find "$bundle/lib" -name 'libOpenImageIO*' -o -name 'libglfw*' -o -name 'libembree*')" ] ||
  fail "the bundle carries a library the runner does not need"

args=(--frames 3 --size 48x32 --clumps 3000)
(cd "$out" && env -i PATH=/usr/bin:/bin HOME=/nonexistent VK_DRIVER_FILES="$VK_DRIVER_FILES" \
  LP_NATIVE_VECTOR_WIDTH="$LP_NATIVE_VECTOR_WIDTH" "$bundle/run.sh" "${args[@]}" --json "$out/bundle.json" --frame-rgba "$out/bundle.rgba" >/dev/null)
"$build/engine/meadow" bench "$root/data/scenes/irises.json" --preset ci "${args[@]}" --json "$out/meadow.json" \
  --frame-rgba "$out/meadow.rgba" >/dev/null

python3 - "$out/bundle.json" "$out/meadow.json" "$out/bundle.rgba" "$out/meadow.rgba" <<'PY'
import json, sys
bundle, meadow = (json.load(open(p)) for p in sys.argv[1:3])
frames = [open(p, "rb").read() for p in sys.argv[3:5]]
assert len(frames[0]) == 48 * 32 * 4, f"the bundle's frame has {len(frames[0])} bytes, not 48x32x4"
assert frames[0] == frames[1], "the bundle's last frame differs from meadow bench's"
pixels = {frames[0][i:i + 4] for i in range(0, len(frames[0]), 4)}
assert len(pixels) > 50 and all(p[3] == 255 for p in pixels), f"{len(pixels)} distinct pixels: not a picture"
for key in ["device", "driver", "width", "height", "clumps", "frames", "frameMs", "gpuMs", "cpuMsPerFrame",
            "uploadBytesPerFrame", "trianglesPerFrame", "instancesPerLod"]:
    assert key in bundle, f"the bundle's bench JSON lacks {key}"
assert bundle["clumps"] == 3000 and bundle["frames"] == 3 and bundle["preset"] == "ci", bundle
assert bundle["frameMs"]["median"] > 0 and all(bundle["gpuMs"][p] > 0 for p in ["animate", "cull", "draw"])
for key in ["clumps", "trianglesPerFrame", "instancesPerLod", "visibleInstances", "uploadBytesPerFrame"]:
    assert bundle[key] == meadow[key], f"{key}: bundle {bundle[key]}, meadow bench {meadow[key]}"
print("bundle and meadow bench agree:", {k: bundle[k] for k in ["clumps", "trianglesPerFrame", "visibleInstances"]})
PY
echo PASS
