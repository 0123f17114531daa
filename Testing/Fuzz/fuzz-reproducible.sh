#!/usr/bin/env bash
# The reproducible fuzz run of the test command (Fuzz.text, Fuzz.filter, Fuzz.las): the same
# commit tries the same inputs in the same order, whatever the environment (on machines of the
# same kind: README.md), so that a run fails for a reason, never by chance, and a failure can
# be run again.
#   fuzz-reproducible.sh FUZZER SEED_CORPUS SCRATCH_CORPUS RUNS [SEED]
# - the scratch corpus, where libFuzzer writes the inputs it finds, is emptied first: a run does
#   not depend on the ones before;
# - a fixed seed (default 1) and number of runs instead of a time limit, no corpus reload (it is
#   timed);
# - the seed corpus given as files in the order of their names (-seed_inputs), not as a folder,
#   whose listing order depends on the file system (and that order changed the run);
# - one thread (OMP_NUM_THREADS=1; FuzzBilateralFilter caps its thread count at it): coverage
#   counted by two threads at once varies from run to run;
# - no comparison-guided mutations (-use_cmp=0, -use_memmem=0): they take values from the
#   comparisons the process makes, among them addresses, its process id and its environment.
# A failing input is written beside the scratch corpus as crash-<sha1> (or leak-, timeout-,
# oom-).
set -euo pipefail
[ $# -ge 4 ] || { echo "usage: $0 FUZZER SEED_CORPUS SCRATCH_CORPUS RUNS [SEED]" >&2; exit 2; }
fuzzer=$1
seeds=$2
scratch=$3
runs=$4
seed=${5:-1}
rm -rf "$scratch"
mkdir -p "$scratch"
seed_files=$(find "$seeds" -maxdepth 1 -type f | LC_ALL=C sort | paste -sd, -)
export OMP_NUM_THREADS=1
exec "$fuzzer" "-seed=$seed" "-runs=$runs" -use_cmp=0 -use_memmem=0 -reload=0 \
  -timeout=10 -rss_limit_mb=2048 "-artifact_prefix=$(dirname "$scratch")/" \
  -print_final_stats=1 "-seed_inputs=$seed_files" "$scratch"
