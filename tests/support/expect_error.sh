#!/usr/bin/env bash
# Runs a command that must fail cleanly: a non-zero exit status, a message on stderr matching
# REGEX, and (with --absent PATH) nothing left at PATH.
#   expect_error.sh REGEX [--absent PATH] -- COMMAND...
set -uo pipefail
regex="$1"; shift
absent=""
if [ "$1" = "--absent" ]; then absent="$2"; shift 2; fi
[ "$1" = "--" ] && shift
stderr_file="$(mktemp)"
"$@" >/dev/null 2>"$stderr_file"
status=$?
message="$(cat "$stderr_file")"; rm -f "$stderr_file"
echo "exit status $status; stderr: $message"
if [ $status -eq 0 ]; then echo "FAIL: expected a non-zero exit status"; exit 1; fi
if [ $status -ge 128 ]; then echo "FAIL: killed by a signal (crash?)"; exit 1; fi
if ! grep -Eq -- "$regex" <<<"$message"; then echo "FAIL: stderr does not match /$regex/"; exit 1; fi
if [ -n "$absent" ] && compgen -G "$absent*" >/dev/null; then echo "FAIL: $absent was left behind"; exit 1; fi
exit 0
