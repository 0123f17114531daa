#!/usr/bin/env bash
# Installs the build into a fresh prefix, then configures, builds and runs the outside project
# Examples/Cxx/External against that prefix alone, with the build tree out of reach.
#   TestExternalProject.sh BUILD_DIR SOURCE_DIR INPUT.ply
set -euo pipefail
build=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
input=$3
scratch=$(mktemp -d /tmp/pcb-external-test.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
fail() { echo "FAILED: $*"; exit 1; }

cmake --install "$build" --prefix "$scratch/prefix" > "$scratch/install.log"
# A clean environment, and no CMake package registry that could point into the build tree.
clean_env=(env -i "PATH=/usr/bin:/bin" "HOME=$scratch")
"${clean_env[@]}" cmake -S "$source_dir/Examples/Cxx/External" -B "$scratch/build" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=$scratch/prefix" \
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF > "$scratch/configure.log" \
  || { cat "$scratch/configure.log"; fail "the outside project does not configure"; }
grep -h "PointCloudBilateral_DIR" "$scratch/build/CMakeCache.txt"
grep -q "PointCloudBilateral_DIR:PATH=$scratch/prefix/" "$scratch/build/CMakeCache.txt" \
  || fail "the package was not found in the prefix"
"${clean_env[@]}" cmake --build "$scratch/build" > "$scratch/build.log" \
  || { cat "$scratch/build.log"; fail "the outside project does not build"; }
if grep -rqF "$build" "$scratch/build/build.ninja"; then
  fail "the outside project's build refers to the build tree"
fi

"${clean_env[@]}" "$scratch/build/DenoiseCloud" "$input" "$scratch/out.vtp" 0.06 0.043 2 \
  || fail "the outside program failed"
[ -s "$scratch/out.vtp" ] || fail "the outside program wrote nothing"
if "${clean_env[@]}" ldd "$scratch/build/DenoiseCloud" | grep -F "$build"; then
  fail "the outside program loads libraries from the build tree"
fi
echo "all checks passed"
