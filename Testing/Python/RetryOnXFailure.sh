#!/usr/bin/env bash
# Runs a ParaView program (pvpython, pvbatch) with its arguments, and runs it again (three runs
# at most) when it died because its render window could not connect to the X server ("bad X
# server connection"): ParaView 5.11 does that now and then under xvfb-run when both cores are
# busy, with or without this project's plugin. Any other outcome is the test's own; the output
# shown is the last run's.
#   RetryOnXFailure.sh PROGRAM ARGUMENTS...
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for attempt in 1 2 3; do
  "$@" > "$log" 2>&1
  status=$?
  if [ "$status" -eq 0 ] || [ "$attempt" -eq 3 ] || ! grep -q "bad X server connection" "$log"; then
    break
  fi
  echo "RetryOnXFailure.sh: run $attempt lost its X server connection; running again" >&2
done
cat "$log"
exit "$status"
