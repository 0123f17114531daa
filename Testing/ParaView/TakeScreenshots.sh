#!/usr/bin/env bash
# Takes the README's screenshots of the ParaView GUI with the plugin: the Properties panel
# (advanced properties shown, after applying the filter with the automatic radius, through the
# menu as a user would) and the Filters menu entry.
#   Testing/ParaView/TakeScreenshots.sh BUILD_DIR OUTPUT_DIR
# Needs xvfb, xdotool, imagemagick and libqt5svg5 (for the icons). Starts its own X server and
# ParaView, and ends only those. The clicks assume ParaView 5.11's default layout.
set -euo pipefail
build=$(cd "$1" && pwd)
mkdir -p "$2"
out=$(cd "$2" && pwd)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
for tool in Xvfb xdotool import; do
  command -v "$tool" > /dev/null || {
    echo "missing $tool: apt-get install xvfb xdotool imagemagick libqt5svg5" >&2; exit 1; }
done

display=:$((RANDOM % 400 + 100))
Xvfb "$display" -screen 0 1500x1000x24 > /dev/null 2>&1 &
xvfb_pid=$!
paraview_pid=
cleanup() {
  [ -n "$paraview_pid" ] && kill "$paraview_pid" 2> /dev/null || true
  kill "$xvfb_pid" 2> /dev/null || true
}
trap cleanup EXIT
export DISPLAY=$display
sleep 1

PCB_READER_ONLY=1 PCB_SOURCE_DIR=$source_dir PV_PLUGIN_PATH=$(dirname "$(find "$build" -name PointCloudBilateral.so -print -quit)") \
  paraview --dr "--script=$source_dir/Testing/ParaView/GUISession.py" > "$out/paraview.log" 2>&1 &
paraview_pid=$!
sleep 12
xdotool key Escape # the welcome dialog
sleep 1
main=$(xdotool search --name "ParaView 5" | head -1)
xdotool windowsize "$main" 1500 1000
xdotool windowmove "$main" 0 0
sleep 2

# As a user would: Filters > Point Cloud (the 13th entry) > Point Cloud Bilateral Filter, then
# Radius 0 (automatic), Normal Radius 0.02, 4 iterations, Apply.
open_point_cloud_menu() {
  xdotool mousemove 193 10 click 1
  sleep 1
  for _ in $(seq 13); do xdotool key Down; sleep 0.1; done
  xdotool key Right
  sleep 1
}
open_point_cloud_menu
xdotool key Return
sleep 2
set_field() {
  xdotool mousemove "$1" "$2" click --repeat 3 1
  xdotool type "$3"
  xdotool key Tab
  sleep 0.3
}
set_field 187 603 0
set_field 206 661 0.02
set_field 223 722 4
xdotool mousemove 48 508 click 1
sleep 4

# Float the Properties dock, make it wide enough for its labels, show advanced properties.
xdotool mousemove 37 477 click --repeat 2 --delay 80 1
sleep 1.5
panel=$(xdotool search --name "^Properties$" | head -1)
xdotool windowsize "$panel" 520 820
xdotool windowmove "$panel" 900 60
sleep 1.5
xdotool mousemove 1397 132 click 1
sleep 1.5
import -window "$panel" -crop 520x430+0+0 "$out/properties_panel.png"

open_point_cloud_menu
import -window root -crop 520x400+190+0 "$out/filters_menu.png"
echo "wrote $out/properties_panel.png and $out/filters_menu.png"
