#!/bin/sh
# Runs a command that must fail, promptly and saying why: succeeds when the command exits with a
# non-zero status before SECONDS (not killed by the time limit) and its output holds PATTERN.
#   ExpectPromptFailure.sh PATTERN SECONDS COMMAND [ARGUMENT...]
pattern=$1
seconds=$2
shift 2
output=$(timeout "$seconds" "$@" 2>&1)
status=$?
printf '%s\n' "$output"
if [ "$status" -eq 124 ]; then
  echo "FAILED: still running after $seconds s (a process left waiting?)"
  exit 1
fi
if [ "$status" -eq 0 ]; then
  echo "FAILED: exited with status 0"
  exit 1
fi
if ! printf '%s\n' "$output" | grep -q -- "$pattern"; then
  echo "FAILED: the output does not say '$pattern'"
  exit 1
fi
echo "ok: exited with status $status, saying '$pattern'"
