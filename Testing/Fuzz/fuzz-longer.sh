#!/usr/bin/env bash
# Random fuzzing for as long as wanted, with all of libFuzzer's means (a random seed, every
# core's threads, comparison-guided mutations): to find new inputs, not for the test command,
# whose runs are short and reproducible (fuzz-reproducible.sh).
#   Testing/Fuzz/fuzz-longer.sh TARGET SECONDS [BUILD_DIR] [LIBFUZZER_OPTIONS...]
# TARGET: text, filter, las, laz or pcd (FuzzPointCloudText, FuzzBilateralFilter, FuzzLAS, FuzzLAZ,
# FuzzPCD). BUILD_DIR: the
# sanitizer build (default build-asan in the source tree, made by .ci/build-sanitizers). The
# corpus it grows stays in BUILD_DIR/Testing/Fuzz/longer-TARGET, so that longer runs build on
# each other; a failing input is written beside it as longer-TARGET-crash-<sha1> (README.md says
# how to add it to the committed corpus).
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 text|filter|las|laz|pcd SECONDS [BUILD_DIR] [LIBFUZZER_OPTIONS...]" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
name=$1
seconds=$2
build=${3:-$here/../../build-asan}
shift $(($# < 3 ? $# : 3))
case "$name" in
  text) fuzzer=FuzzPointCloudText ;;
  filter) fuzzer=FuzzBilateralFilter ;;
  las) fuzzer=FuzzLAS ;;
  laz) fuzzer=FuzzLAZ ;;
  pcd) fuzzer=FuzzPCD ;;
  *) echo "$0: unknown target '$name' (text, filter, las, laz or pcd)" >&2; exit 2 ;;
esac
[ -x "$build/bin/$fuzzer" ] || { echo "$0: no $build/bin/$fuzzer (run .ci/build-sanitizers)" >&2; exit 2; }
work="$build/Testing/Fuzz"
mkdir -p "$work/longer-$name"
exec "$build/bin/$fuzzer" "-max_total_time=$seconds" -timeout=10 -rss_limit_mb=2048 \
  "-artifact_prefix=$work/longer-$name-" -print_final_stats=1 "$@" \
  "$work/longer-$name" "$here/corpus/$name"
