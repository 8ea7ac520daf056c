#!/usr/bin/env bash
# Renders the golden scene (golden.sh's field_afternoon) under every setting lavapipe can be made
# to compile for on this machine: vector widths 256 and 128, each with GALLIUM_OVERRIDE_CPU_CAPS
# unset and set to each value Mesa 22.3 accepts, all sharing one shader cache. Every render runs under a guard allocator, so a
# driver that writes past a heap block fails here instead of in a user's render, and must match
# the golden image. Settings below AVX on a CPU that has AVX, and vector widths other than 128 and
# 256, must be refused with a clear message (engine/vk/driver_workarounds.h).
#
#   lavapipe_settings.sh MEADOW IMAGE_COMPARE OUTDIR
# GUARD=malloc-check (default): glibc's checking allocator, which finds a write past a block when
#   the block is freed (seconds a render).
# GUARD=efence: Electric Fence, which stops the writing instruction itself (minutes a render;
#   apt-get install electric-fence).
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
meadow="$1"; compare="$2"; outdir="$3"
mkdir -p "$outdir"

case "${GUARD:-malloc-check}" in
  malloc-check)
    guard=(LD_PRELOAD=libc_malloc_debug.so.0 GLIBC_TUNABLES=glibc.malloc.check=3 MALLOC_PERTURB_=165) ;;
  efence)
    guard=(LD_PRELOAD=libefence.so EF_ALIGNMENT=16) ;;
  *) echo "lavapipe_settings.sh: GUARD must be malloc-check or efence" >&2; exit 2 ;;
esac

# One shader-cache root for the whole sweep, as a user's ~/.cache is: Mesa 22.3 keys vertex code by
# the CPU caps but not by the vector width, so a 128-bit render after a 256-bit one would run the
# 256-bit code and overrun its buffer, unless meadow keeps each width's cache apart. 256 goes first.
cache_root="$(mktemp -d)"
trap 'rm -rf "$cache_root"' EXIT
export MESA_SHADER_CACHE_DIR="$cache_root"
unset MESA_SHADER_CACHE_DISABLE

has_avx=0
grep -qw avx /proc/cpuinfo && has_avx=1
failures=0
for width in 256 128; do
  for caps in unset nosse sse sse2 sse3 ssse3 sse4.1 avx; do
    setting="LP_NATIVE_VECTOR_WIDTH=$width GALLIUM_OVERRIDE_CPU_CAPS=$caps"
    env_caps=(GALLIUM_OVERRIDE_CPU_CAPS="$caps")
    [ "$caps" = unset ] && env_caps=(-u GALLIUM_OVERRIDE_CPU_CAPS)
    log="$outdir/render-$width-$caps.log"
    env "${env_caps[@]}" LP_NATIVE_VECTOR_WIDTH="$width" "${guard[@]}" \
      bash "$here/../golden/golden.sh" "$meadow" "$compare" "$outdir/$width-$caps" field_afternoon >"$log" 2>&1
    status=$?
    if [ "$has_avx" = 1 ] && [ "$caps" != unset ] && [ "$caps" != avx ]; then
      # Below AVX on an AVX CPU: a clean refusal, exit status 1, naming the setting.
      if [ "$status" = 1 ] && grep -q "meadow: error: GALLIUM_OVERRIDE_CPU_CAPS=$caps: lavapipe" "$log"; then
        echo "ok      $setting (refused, as it must be)"
      else
        echo "FAILED  $setting: expected a clean refusal, got exit status $status:"; tail -3 "$log"
        failures=$((failures + 1))
      fi
    elif [ "$status" = 0 ]; then
      echo "ok      $setting (matches the golden)"
    else
      echo "FAILED  $setting: exit status $status:"; tail -3 "$log"
      failures=$((failures + 1))
    fi
  done
done
# Widths lavapipe cannot compile for (it crashes at the first compute pipeline): a clean refusal,
# exit status 1, naming the setting, and no image.
for width in 512 64 0; do
  setting="LP_NATIVE_VECTOR_WIDTH=$width"
  log="$outdir/render-$width.log"
  rm -f "$outdir/refused-$width.png"
  LP_NATIVE_VECTOR_WIDTH="$width" "$meadow" render "$here/../../../data/scenes/irises.json" --preset ci --size 64x36 \
    --out "$outdir/refused-$width.png" >"$log" 2>&1
  status=$?
  if [ "$status" = 1 ] && grep -q "meadow: error: LP_NATIVE_VECTOR_WIDTH=$width: lavapipe" "$log" &&
    [ ! -e "$outdir/refused-$width.png" ]; then
    echo "ok      $setting (refused, as it must be)"
  else
    echo "FAILED  $setting: expected a clean refusal and no image, got exit status $status:"; tail -3 "$log"
    failures=$((failures + 1))
  fi
done
[ "$failures" = 0 ] || { echo "$failures setting(s) failed; logs in $outdir"; exit 1; }
