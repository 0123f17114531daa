#!/usr/bin/env bash
# Plays PanelChecks.xml in the ParaView GUI (the plugin auto-loaded) after PanelSession.py, and
# runs it again (three runs at most) when ParaView lost its X server connection, which ParaView
# 5.11 does now and then under a busy xvfb-run. Fails when a check fails (ParaView's exit status)
# or when GDAL printed its "ERROR 4" (opening the LAS file).
#   TestPanel.sh PLUGIN_DIR SOURCE_DIR SCRATCH_DIR
set -uo pipefail
plugin_dir=$1 source_dir=$2 scratch=$3
mkdir -p "$scratch"
for attempt in 1 2 3; do
  PCB_SCRATCH=$scratch PCB_SOURCE_DIR=$source_dir PV_PLUGIN_PATH=$plugin_dir paraview --dr \
    "--script=$source_dir/Testing/ParaView/PanelSession.py" \
    "--test-script=$source_dir/Testing/ParaView/PanelChecks.xml" \
    "--test-directory=$scratch" --exit > "$scratch/paraview.log" 2>&1
  status=$?
  if [ "$status" -eq 0 ] || [ "$attempt" -eq 3 ] ||
    ! grep -q -E "bad X server connection|X Error of failed request" "$scratch/paraview.log"; then
    break
  fi
  echo "TestPanel.sh: run $attempt lost its X server connection; running again"
done
cat "$scratch/paraview.log"
# Opening the LAS file asked no GDAL reader (which printed "ERROR 4: ... not recognized").
if grep -q "^ERROR 4" "$scratch/paraview.log"; then
  echo "FAILED: opening a LAS file printed GDAL's ERROR 4"
  exit 1
fi
exit "$status"
