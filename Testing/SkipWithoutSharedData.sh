#!/usr/bin/env bash
# Runs a test that reads the shared data (the authors' reference outputs, the LAS samples, the
# real scans), or reports it skipped, with the reason, when that data is not configured or not there: exit 77,
# the SKIP_RETURN_CODE of these tests, so that ctest lists them as "Skipped" instead of failing
# them (and no program is started with an empty or missing path).
#   SkipWithoutSharedData.sh VARIABLE FOLDER [FILE...] -- COMMAND [ARGUMENTS...]
# VARIABLE is the setting that names FOLDER (PCB_REFERENCE_DIR, PCB_LAS_DATA_DIR,
# PCB_REAL_DATA_DIR), for the message; each FILE is a path inside FOLDER that the test needs.
set -euo pipefail
variable=$1
folder=$2
shift 2
required=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  required+=("$1")
  shift
done
[ $# -gt 1 ] || { echo "usage: $0 VARIABLE FOLDER [FILE...] -- COMMAND [ARGUMENTS...]" >&2; exit 2; }
shift
skip() {
  echo "skipped: $*"
  exit 77
}
[ -n "$folder" ] || skip "$variable is not set (configure with -D$variable=FOLDER)"
[ -d "$folder" ] || skip "$variable=$folder is not a folder"
for file in "${required[@]}"; do
  [ -e "$folder/$file" ] || skip "$variable=$folder has no $file"
done
exec "$@"
