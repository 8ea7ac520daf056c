#!/usr/bin/env bash
# All of meadow's tests: installs what is missing, builds with warnings as errors, runs ctest.
#   scripts/test.sh [ctest arguments...]   e.g. scripts/test.sh -L unit
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-ci"
bash "$root/scripts/build.sh" "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMEADOW_WERROR=ON
cd "$build"
ctest --output-on-failure --parallel "$(nproc)" "$@"
