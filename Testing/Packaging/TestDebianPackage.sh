#!/usr/bin/env bash
# Builds the Debian package (cpack -G DEB) into a scratch folder, unpacks it with dpkg -x (not
# installed) and uses it from there, with the build tree out of reach:
# - the control data: the package and its Depends pinned to the ParaView it was built against;
# - every path it must install, and no file another installed package owns;
# - the plugin auto-loaded, through the package's paraview.conf, by pvpython, pvbatch and the GUI
#   started from the unpacked usr/bin (symbolic links to Debian's programs: ParaView reads
#   paraview.conf beside the path it was started from), and not loaded without that file;
# - the Python package in /usr/bin/python3 and pvpython, whose installed folder is on both
#   interpreters' default path (PYTHONPATH is set here only because the package is not installed);
# - the programs, and every ELF file's libraries found (ldd) with the package's own ones inside
#   the unpacked tree: RUNPATH $ORIGIN, no LD_LIBRARY_PATH anywhere in this test;
# - find_package(PointCloudBilateral) from an outside project (Examples/Cxx/External), built and
#   run against the unpacked tree.
# Needs an X display for the GUI (ctest runs under xvfb-run).
#   TestDebianPackage.sh BUILD_DIR SOURCE_DIR PREFIX BINDIR LIBDIR PLUGIN_SUBDIR PYTHON_SUBDIR
set -euo pipefail
build=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
prefix=$3 bindir=$4 libdir=$5 plugin_subdir=$6 python_subdir=$7
here=$(cd "$(dirname "$0")" && pwd)
scratch=$(mktemp -d /tmp/pcb-deb-test.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
fail() { echo "FAILED: $*"; exit 1; }
ok() { echo "ok:     $*"; }

# The package, built into the scratch folder (cpack -B), nothing written in the build tree.
(cd "$scratch" && cpack --config "$build/CPackConfig.cmake" -G DEB -B "$scratch/cpack" \
  > cpack.log 2>&1) || { cat "$scratch/cpack.log"; fail "cpack -G DEB"; }
deb=$(find "$scratch/cpack" -maxdepth 1 -name 'pointcloud-bilateral_*.deb' -print -quit)
[ -n "$deb" ] || fail "no .deb written: $(ls "$scratch/cpack")"
ok "built $(basename "$deb") ($(stat -c %s "$deb") bytes)"

# Depends pins the exact ParaView it was built against.
paraview_version=$(dpkg-query -W -f='${Version}' paraview)
depends=$(dpkg-deb -f "$deb" Depends)
for package in paraview python3-paraview; do
  grep -qF "$package (= $paraview_version)" <<< "$depends" \
    || fail "Depends does not pin $package (= $paraview_version): $depends"
done
ok "Depends: $depends"

root=$scratch/root
dpkg -x "$deb" "$root"
usr=$root$prefix
plugins=$usr/$libdir/$plugin_subdir
expected=(
  "$bindir/pcbilateral"
  "$bindir/paraview.conf"
  "$libdir/$plugin_subdir/PointCloudBilateral/PointCloudBilateral.so"
  "$libdir/$plugin_subdir/PointCloudBilateral.plugins.xml"
  "$python_subdir/pointcloudbilateral/__init__.py"
  "$python_subdir/pointcloudbilateral/vtkFiltersPointCloudBilateral.so"
  "$libdir/cmake/PointCloudBilateral/PointCloudBilateralConfig.cmake"
  "include/pointcloudbilateral/vtkPointCloudBilateralFilter.h"
  "share/pointcloudbilateral/examples/denoise.py"
)
for path in "${expected[@]}"; do
  [ -f "$usr/$path" ] || fail "the package has no $prefix/$path"
done
ok "the package installs ${#expected[@]} expected paths under $prefix"

# Nothing in it belongs to another installed package (paraview's files are left alone).
mapfile -t files < <(cd "$root" && find . ! -type d | sed 's|^\.||')
owners=$(dpkg -S "${files[@]}" 2> /dev/null | grep -v '^pointcloud-bilateral: ' || true)
[ -z "$owners" ] || fail "files of other packages: $owners"
ok "none of its ${#files[@]} files belongs to another package"

# ParaView's programs as if installed beside paraview.conf (links: ParaView takes the folder of
# the path it was started with).
for program in pvpython pvbatch paraview; do
  ln -s "$(readlink -f "$(command -v $program)")" "$usr/$bindir/$program"
done
# (The X display, for the GUI, is all this takes from the environment.)
clean_env=(env -i "PATH=/usr/bin:/bin" "HOME=$scratch/home" "PCB_ROOT=$root" "DISPLAY=${DISPLAY:-}"
  "XAUTHORITY=${XAUTHORITY:-}")
mkdir -p "$scratch/home"
cd "$scratch"
retry=$source_dir/Testing/Python/RetryOnXFailure.sh
for program in pvpython pvbatch; do
  "${clean_env[@]}" "$retry" "$usr/$bindir/$program" "$here/CheckAutoLoaded.py" \
    || fail "$program from the package's $bindir"
done
# The GUI writes its lines to a log (its standard output is ParaView's).
for attempt in 1 2 3; do
  "${clean_env[@]}" "PCB_LOG=$scratch/gui.log" "$usr/$bindir/paraview" --dr \
    "--script=$here/CheckAutoLoaded.py" --exit > gui.out 2>&1 || true
  [ -s gui.log ] || ! grep -q "bad X server connection" gui.out || continue
  break
done
[ -s gui.log ] || { cat gui.out; fail "the GUI wrote no log"; }
cat gui.log
! grep -q "^FAILED" gui.log || fail "the GUI"
# Control: the same programs started from a folder without paraview.conf do not load it.
mkdir -p "$scratch/no-conf"
ln -s "$(readlink -f "$(command -v pvpython)")" "$scratch/no-conf/pvpython"
"${clean_env[@]}" PCB_EXPECT_ABSENT=1 "$retry" "$scratch/no-conf/pvpython" \
  "$here/CheckAutoLoaded.py" || fail "pvpython loaded the plugin without paraview.conf"

# The Python package, where both interpreters look by default once installed.
installed_python=$prefix/$python_subdir
for python in /usr/bin/python3 pvpython; do
  "${clean_env[@]}" "$python" -c "import sys; sys.exit('$installed_python' not in sys.path)" \
    || fail "$installed_python is not on $python's default path"
done
ok "$installed_python is on the default path of /usr/bin/python3 and pvpython"
cat > import.py << 'PYTHON'
import os, sys
import pointcloudbilateral
from pointcloudbilateral import vtkPointCloudBilateralFilter
from vtkmodules.vtkFiltersSources import vtkPointSource
source = vtkPointSource()
source.SetNumberOfPoints(300)
bilateral = vtkPointCloudBilateralFilter()
bilateral.SetInputConnection(source.GetOutputPort())
bilateral.Update()
assert pointcloudbilateral.__file__.startswith(os.environ["PCB_ROOT"] + "/"), pointcloudbilateral.__file__
print(f"ok:     {sys.executable}: pointcloudbilateral from {os.path.dirname(pointcloudbilateral.__file__)}, "
      f"{bilateral.GetOutput().GetNumberOfPoints()} points filtered")
PYTHON
for python in /usr/bin/python3 "$usr/$bindir/pvpython"; do
  "${clean_env[@]}" "PYTHONPATH=$usr/$python_subdir" "$python" import.py \
    || fail "import pointcloudbilateral in $python"
done

# The programs, and every ELF file's libraries: found, the package's own inside the tree.
"${clean_env[@]}" "$usr/$bindir/pcbilateral" "$source_dir/Data/cube_noise0.5.ply" cli.vtp \
  -r 0.06 > cli.log || fail "pcbilateral from the package"
[ -s cli.vtp ] || fail "pcbilateral wrote nothing"
ok "$prefix/$bindir/pcbilateral runs"
elf_count=0
while IFS= read -r file; do
  head -c 4 "$file" | grep -q ELF || continue
  elf_count=$((elf_count + 1))
  libraries=$(env -i PATH=/usr/bin:/bin ldd "$file")
  ! grep -q "not found" <<< "$libraries" || fail "$file: $(grep "not found" <<< "$libraries")"
  own=$(grep -E 'PointCloudBilateral' <<< "$libraries" || true)
  if [ -n "$own" ] && grep -v -F "=> $root/" <<< "$own"; then
    fail "$file loads the package's libraries from outside the unpacked tree"
  fi
  ! grep -qF "$build" <<< "$libraries" || fail "$file loads from the build tree"
done < <(find "$usr" -type f)
ok "ldd: the libraries of $elf_count ELF files are found, the package's own in the tree"

# find_package(PointCloudBilateral) from an outside project.
"${clean_env[@]}" cmake -S "$source_dir/Examples/Cxx/External" -B external -G Ninja \
  -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=$usr" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
  > external-configure.log 2>&1 || { cat external-configure.log; fail "the outside project"; }
grep -q "PointCloudBilateral_DIR:PATH=$usr/$libdir/cmake/PointCloudBilateral" \
  external/CMakeCache.txt || fail "find_package did not take the package's config"
"${clean_env[@]}" cmake --build external > external-build.log 2>&1 \
  || { cat external-build.log; fail "the outside project does not build"; }
"${clean_env[@]}" external/DenoiseCloud "$source_dir/Data/cube_noise0.5.ply" external.vtp \
  0.06 0.043 2 || fail "the outside program failed"
[ -s external.vtp ] || fail "the outside program wrote nothing"
ok "find_package(PointCloudBilateral) in $prefix/$libdir/cmake: DenoiseCloud built and run"
echo "all checks passed"
