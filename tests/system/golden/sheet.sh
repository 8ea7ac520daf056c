#!/usr/bin/env bash
# A sheet (`meadow sheet`, under the validation layer) must be an image of SIZE that is not blank.
#   sheet.sh MEADOW IMAGE_COMPARE OUT_PNG SIZE [meadow sheet arguments before --out...]
set -euo pipefail
meadow="$1"; compare="$2"; png="$3"; size="$4"
shift 4
mkdir -p "$(dirname "$png")"
"$meadow" sheet "$@" --out "$png" --validation
"$compare" "$png" --not-blank --size "$size"
