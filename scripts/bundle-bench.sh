#!/usr/bin/env bash
# Bundles the bench runner (meadow-bench, engine/app/bench_main.cpp) with everything it needs to
# benchmark the default scene on a machine that has a Vulkan GPU driver but not meadow's Debian
# packages: the binary (stripped), the shared libraries it links besides the C library (the Vulkan
# loader, TBB, the C++ runtime), the scene, its precomputed library, the camera
# paths, and two scripts:
#   run.sh [meadow-bench options]   the bench runner on the bundled scene and library, e.g.
#                                   run.sh --clumps 1000000 --size 1920x1080 --json out.json
#   sweep.sh [OUT] [COUNTS...]      scripts/bench-sweep.sh at 1920x1080 from 10 thousand to a
#                                   million clumps (JSON per run and a Markdown table in OUT,
#                                   default ./bench-sweep; the plot where python3 has matplotlib);
#                                   --far-radius PX before the counts sets the far field's
#                                   radius (0: off; default bench's, 28 px)
# The bundle is a folder and a .tar.gz beside it.
#   scripts/bundle-bench.sh [--preset full|ci] [--build-dir DIR] [--out DIR] [--no-build]
# Defaults: the full preset, build-ci (built first with scripts/build.sh unless --no-build),
# out/bench-bundle. On the GPU machine: tar xzf meadow-bench-bundle.tar.gz; meadow-bench-bundle/run.sh --help
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
preset=full
build="$root/build-ci"
out="$root/out/bench-bundle"
do_build=1
while [ $# -gt 0 ]; do
  case "$1" in
    --preset) preset="$2"; shift 2 ;;
    --build-dir) build="$(cd "$2" && pwd)"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --no-build) do_build=""; shift ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "bundle-bench: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case "$preset" in full|ci) ;; *) echo "bundle-bench: --preset '$preset' is not full or ci" >&2; exit 2 ;; esac

if [ -n "$do_build" ]; then
  bash "$root/scripts/build.sh" "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
meadow="$build/engine/meadow"
runner="$build/engine/meadow-bench"
for f in "$meadow" "$runner"; do
  [ -x "$f" ] || { echo "bundle-bench: $f is missing: build first (or leave out --no-build)" >&2; exit 1; }
done

scene="$root/data/scenes/irises.json"
# The library as meadow's cache holds it (built now if missing: about 90 s for the full preset).
library="$("$meadow" precompute "$scene" --preset "$preset")"

name=meadow-bench-bundle
mkdir -p "$out"
out="$(cd "$out" && pwd)"
dir="$out/$name"
rm -rf "$dir" "$dir.partial" "$out/$name.tar.gz"
stage="$dir.partial"
mkdir -p "$stage/bin" "$stage/lib" "$stage/cache" "$stage/scenes" "$stage/paths" "$stage/scripts"

strip --strip-unneeded -o "$stage/bin/meadow-bench" "$runner"
# Every shared library the runner loads, but the C library and the dynamic loader, which any
# Linux machine has in a version the runner accepts (glibc is backward compatible), and which must
# match each other and the kernel. The Vulkan loader goes along; the GPU's driver (its ICD) is the
# machine's.
ldd "$runner" | awk '$2 == "=>" && $3 ~ /^\// { print $3 }' | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|ld-linux*) continue ;;
  esac
  cp -L "$lib" "$stage/lib/"
done
cp "$scene" "$stage/scenes/"
cp "$library" "$stage/cache/"
cp "$root"/data/paths/*.json "$stage/paths/"
cp "$root/scripts/bench-sweep.sh" "$stage/scripts/"

cat >"$stage/run.sh" <<EOF
#!/usr/bin/env bash
# meadow's bench runner on the bundled scene ($(basename "$scene"), preset $preset) and its library.
#   run.sh [options of meadow bench: --clumps N --frames F --size WxH --driver gpu|cpu
#           --camera-path paths/flyover.json --json OUT ...]      run.sh --help tells more
set -euo pipefail
here="\$(cd "\$(dirname "\$0")" && pwd)"
export LD_LIBRARY_PATH="\$here/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
export MEADOW_CACHE_DIR="\$here/cache"
# NVIDIA's container toolkit puts the driver's manifest outside the loader's search path.
if [ -z "\${VK_DRIVER_FILES:-}\${VK_ICD_FILENAMES:-}" ] && [ ! -d /usr/share/vulkan/icd.d ] && [ ! -d /etc/vulkan/icd.d ] &&
   [ -f /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ]; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
if [ "\${1:-}" = --help ] || [ "\${1:-}" = -h ]; then exec "\$here/bin/meadow-bench" --help; fi
exec "\$here/bin/meadow-bench" "\$here/scenes/$(basename "$scene")" --preset $preset "\$@"
EOF
cat >"$stage/sweep.sh" <<'EOF'
#!/usr/bin/env bash
# The field-size sweep at 1920x1080 (docs/BENCHMARKS.md, The numbers meadow holds itself to):
# meadow-bench from 10 thousand to a million clumps, 30 frames each, JSON per run and a Markdown
# table (a plot too where matplotlib is).
#   sweep.sh [OUT] [--far-radius PX] [COUNTS...]     OUT default ./bench-sweep
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="${1:-$PWD/bench-sweep}"
shift || true
# The scene and preset are the bundle's (run.sh adds them); bench-sweep passes its own copy too,
# which run.sh's come before, so the bundle's scene is the one benchmarked.
exec bash "$here/scripts/bench-sweep.sh" --bench "$here/scripts/run-scene.sh" --scene bundled \
  --size 1920x1080 --frames 30 --out "$out" "$@"
EOF
# bench-sweep calls CMD SCENE --preset P ...: drop its scene and preset, keep the rest.
cat >"$stage/scripts/run-scene.sh" <<'EOF'
#!/usr/bin/env bash
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shift # the scene bench-sweep names
[ "${1:-}" = --preset ] && shift 2
exec "$here/run.sh" "$@"
EOF
chmod +x "$stage/run.sh" "$stage/sweep.sh" "$stage/scripts/run-scene.sh"

mv "$stage" "$dir"
tar -C "$out" -czf "$out/$name.tar.gz.partial" "$name"
mv "$out/$name.tar.gz.partial" "$out/$name.tar.gz"
echo "bundle-bench: $dir ($(du -sh "$dir" | cut -f1)), $out/$name.tar.gz ($(du -h "$out/$name.tar.gz" | cut -f1))" >&2
echo "$out/$name.tar.gz"
