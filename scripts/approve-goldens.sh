#!/usr/bin/env bash
# Renders every golden case and overwrites tests/system/golden/images/ with the result. Run it only
# after looking at the new images (they are printed at the end); CI never writes goldens.
#   scripts/approve-goldens.sh [BUILD_DIR]   (default: build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
[ -x "$build/engine/meadow" ] && [ -x "$build/tests/support/meadow_image_compare" ] || {
  echo "approve-goldens: build meadow first (bash scripts/test.sh, or cmake --build $build)" >&2; exit 1; }
# The same pinning as the tests (tests/CMakeLists.txt): lavapipe, 128-bit vectors.
icd="$(ls /usr/share/vulkan/icd.d/lvp_icd.*.json | head -n 1)"
export VK_ICD_FILENAMES="$icd" VK_DRIVER_FILES="$icd" LP_NATIVE_VECTOR_WIDTH=128
export MEADOW_CACHE_DIR="$build/test-cache"
for name in $(bash "$root/tests/system/golden/golden.sh" --list); do
  bash "$root/tests/system/golden/golden.sh" "$build/engine/meadow" "$build/tests/support/meadow_image_compare" \
    "$build/test-output/golden" "$name" --approve
done
git -C "$root" status --short tests/system/golden/images
