#!/usr/bin/env bash
# Installs the build into a fresh prefix and uses it with the build tree out of reach: the
# installed programs, plugin and Python package must load nothing from the build tree.
#   TestInstall.sh BUILD_DIR INPUT.ply
set -euo pipefail
build=$(cd "$1" && pwd)
input=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
# Outside the build tree, removed at the end.
scratch=$(mktemp -d /tmp/pcb-install-test.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
prefix=$scratch/prefix
cmake --install "$build" --prefix "$prefix" > "$scratch/install.log"

fail() { echo "FAILED: $*"; exit 1; }
plugin=$(find "$prefix" -name PointCloudBilateral.so -print -quit)
package=$(find "$prefix" -type d -name pointcloudbilateral -path '*dist-packages*' -print -quit)
[ -n "$plugin" ] || fail "no plugin installed"
[ -n "$package" ] || fail "no Python package installed"
echo "plugin:  $plugin"
echo "package: $package"

# Nothing installed may look for libraries in the build tree.
while IFS= read -r binary; do
  if readelf -d "$binary" 2>/dev/null | grep -E 'RPATH|RUNPATH' | grep -qF "$build"; then
    fail "$binary searches the build tree: $(readelf -d "$binary" | grep -E 'RPATH|RUNPATH')"
  fi
done < <(find "$prefix" -type f \( -name '*.so*' -o -perm -u+x \))
echo "ok: no installed binary searches the build tree"

# A clean environment: only the prefix, no build paths.
clean_env=(env -i "PATH=/usr/bin:/bin" "HOME=$scratch")
cd "$scratch"

# The installed pvpython example finds the plugin next to itself.
"${clean_env[@]}" pvpython "$prefix/share/pointcloudbilateral/examples/denoise.py" \
  "$input" "$scratch/denoised.vtp" --radius 0.06 --iterations 2 | tee pvpython.log
grep -qF "plugin: $prefix/" pvpython.log || fail "the example did not load the installed plugin"
[ -s "$scratch/denoised.vtp" ] || fail "the example wrote nothing"

# The plugin through PV_PLUGIN_PATH, and the Python package, load nothing from the build tree.
cat > check_loaded.py <<PYTHON
import sys
from paraview import simple
from pointcloudbilateral import vtkPointCloudBilateralFilter
assert hasattr(simple, "PointCloudBilateralFilter"), "the plugin did not auto-load"
loaded = [line.split()[-1] for line in open("/proc/self/maps") if "$build" in line]
print("files loaded from the build tree:", sorted(set(loaded)) or "none")
sys.exit(1 if loaded else 0)
PYTHON
"${clean_env[@]}" "PV_PLUGIN_PATH=$(dirname "$plugin")" "PYTHONPATH=$(dirname "$package")" \
  pvpython check_loaded.py || fail "pvpython used the build tree"

# /usr/bin/python3 with only the installed package.
"${clean_env[@]}" "PYTHONPATH=$(dirname "$package")" /usr/bin/python3 \
  "$prefix/share/pointcloudbilateral/examples/numpy_roundtrip.py" || fail "python3 example"

# The installed command-line program.
"${clean_env[@]}" "$prefix/bin/pcbilateral" "$input" "$scratch/cli.vtp" -r 0.06 > cli.log \
  || fail "the installed pcbilateral failed"
echo "ok: the installed pcbilateral runs"
echo "all checks passed"
