#!/usr/bin/env bash
# Formats meadow's C++ sources with clang-format (.clang-format), or checks that they are.
#   scripts/format.sh          format every tracked .cpp and .h in place
#   scripts/format.sh --check  change nothing; fail naming each file that is not formatted (.ci/run)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
bash scripts/install-deps.sh
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if [[ "${1:-}" == "--check" ]]; then
    clang-format --dry-run --Werror "${files[@]}"
    echo "format: ${#files[@]} files formatted as .clang-format says"
else
    clang-format -i "${files[@]}"
fi
