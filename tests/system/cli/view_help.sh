#!/usr/bin/env bash
# `meadow view --help` names every key and option of the walkthrough.
#   view_help.sh MEADOW
set -euo pipefail
help="$("$1" view --help)"
for want in 'W A S D' F12 F11 'Esc' '--script FILE' '--camera-path FILE' 'move DX DY'; do
  grep -qF -- "$want" <<<"$help" || { echo "missing: $want"; exit 1; }
done
