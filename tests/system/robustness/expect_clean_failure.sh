#!/usr/bin/env bash
# Runs a command on a bad input, which must fail cleanly:
#   - a non-zero exit status, not a signal (no crash, no sanitizer abort),
#   - one message on stderr, "meadow: error: ..." (a meadow::Error, not an "internal error"),
#     matching REGEX (which names the file and the problem),
#   - nothing on stdout (no partial result),
#   - with --absent PATH, nothing at PATH* afterwards (no partial output file).
#   expect_clean_failure.sh REGEX [--absent PATH] -- COMMAND...
set -uo pipefail
export LC_ALL=C # messages are compared byte by byte, whatever they hold
regex="$1"; shift
absent=""
if [ "$1" = "--absent" ]; then absent="$2"; shift 2; fi
[ "$1" = "--" ] && shift
stdout_file="$(mktemp)"; stderr_file="$(mktemp)"
"$@" >"$stdout_file" 2>"$stderr_file"
status=$?
stdout="$(cat "$stdout_file")"
# Progress lines ("meadow: [  0.1 s] ...") may come before the error.
message="$(grep -v '^meadow: \[' "$stderr_file")"
rm -f "$stdout_file" "$stderr_file"
echo "exit status $status; stderr: $message"
fail() { echo "FAIL: $1"; exit 1; }
[ $status -ne 0 ] || fail "expected a non-zero exit status"
[ $status -lt 128 ] || fail "killed by signal $((status - 128)) (a crash)"
[ -z "$stdout" ] || fail "something was written on stdout: $stdout"
[ "$(grep -c . <<<"$message")" -eq 1 ] || fail "expected exactly one message line on stderr"
grep -q '^meadow: error: ' <<<"$message" || fail "the message is not a meadow error (internal error?)"
grep -Eq -- "$regex" <<<"$message" || fail "stderr does not match /$regex/"
if [ -n "$absent" ] && compgen -G "$absent*" >/dev/null; then fail "$absent was left behind"; fi
exit 0
