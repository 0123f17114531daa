#!/usr/bin/env bash
# Configures the project with BUILD_TESTING=OFF in a scratch folder and checks that nothing of
# the tests is looked for or built: no pvpython, paraview or Eigen lookup of ours, no test target.
#   CheckConfigureWithoutTests.sh SOURCE_DIR
set -euo pipefail
source_dir=$(cd "$1" && pwd)
scratch=$(mktemp -d /tmp/pcb-no-tests.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
fail() { echo "FAILED: $*"; exit 1; }
cmake -S "$source_dir" -B "$scratch" -G Ninja -DBUILD_TESTING=OFF > "$scratch/configure.log" 2>&1 \
  || { cat "$scratch/configure.log"; fail "the project does not configure without tests"; }
for variable in PVPYTHON_EXECUTABLE PVBATCH_EXECUTABLE PARAVIEW_EXECUTABLE Eigen3_DIR; do
  if grep -q "^$variable:" "$scratch/CMakeCache.txt"; then
    fail "$variable was looked for"
  fi
done
targets=$(cmake --build "$scratch" --target help)
for target in pcbilateral PointCloudBilateral FiltersPointCloudBilateral; do
  grep -q "^$target:" <<< "$targets" || fail "no $target target"
done
for target in TestPointCloudBilateralFilter TestKernel pcb_benchmark TestBilateralImages; do
  if grep -q "^$target:" <<< "$targets"; then
    fail "the test target $target is built"
  fi
done
echo "all checks passed"
