#!/usr/bin/env bash
# Runs a Python script inside the ParaView GUI (with the plugin auto-loaded) that writes
# "ok: ..." / "FAILED: ..." lines to the file PCB_LOG; prints them and fails on any FAILED line,
# none at all, or an exception that stopped the script. Needs an X display (the test command runs ctest under xvfb-run).
#   TestGUIScript.sh PLUGIN_DIR SOURCE_DIR SCRIPT LOG
set -euo pipefail
plugin_dir=$1 source_dir=$2 script=$3 log=$4
# Run again (three runs at most) when ParaView lost its X server connection, which ParaView 5.11
# does now and then under a busy xvfb-run.
for attempt in 1 2 3; do
  rm -f "$log"
  PCB_LOG=$log PCB_SOURCE_DIR=$source_dir PV_PLUGIN_PATH=$plugin_dir \
    paraview --dr "--script=$script" --exit > "$log.paraview" 2>&1 || true
  if [ -s "$log" ] || [ "$attempt" -eq 3 ] ||
    ! grep -q -E "bad X server connection|X Error of failed request" "$log.paraview"; then
    break
  fi
  echo "TestGUIScript.sh: run $attempt lost its X server connection; running again"
done
cat "$log"
# A script that stopped on an exception wrote only the checks before it.
if grep -q "^Traceback" "$log.paraview"; then
  echo "FAILED: the script raised an exception:"
  sed -n '/^Traceback/,$p' "$log.paraview"
  exit 1
fi
grep -q "^ok:" "$log" && ! grep -q "^FAILED" "$log"
