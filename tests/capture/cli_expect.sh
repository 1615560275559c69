#!/bin/sh
# Usage: cli_expect.sh EXIT_CODE PATTERN COMMAND... : runs COMMAND, passes if it exits with
# EXIT_CODE and its output (stdout + stderr) matches the extended regular expression PATTERN.
want=$1 pattern=$2
shift 2
out=$("$@" 2>&1)
rc=$?
printf '%s\n' "$out"
if [ "$rc" -ne "$want" ]; then
  echo "cli_expect: exit code $rc, expected $want" >&2
  exit 1
fi
if ! printf '%s\n' "$out" | grep -Eq -- "$pattern"; then
  echo "cli_expect: output does not match '$pattern'" >&2
  exit 1
fi
