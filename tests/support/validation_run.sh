#!/usr/bin/env bash
# Runs a meadow command with the Khronos validation layer (synchronization validation included)
# and passes only if it exits 0 and the layer was on and reported nothing.
#   validation_run.sh MEADOW ARGS...
set -uo pipefail
log="$(mktemp)"
"$@" --validation 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
summary="$(grep "validation layer on" "$log")"
rm -f "$log"
[ "$status" -eq 0 ] || { echo "FAIL: exit status $status (3 means the layer reported messages)"; exit 1; }
grep -q ": 0 messages" <<<"$summary" || { echo "FAIL: the validation layer did not run or was not silent"; exit 1; }
