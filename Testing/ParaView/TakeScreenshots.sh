#!/usr/bin/env bash
# Takes screenshots of the ParaView GUI with the plugin, driven as a user would: the sample opened
# (its points shown), the Filters menu entry (filters_menu.png, in docs/usage.md), a bad radius
# (error.png: one message, nothing shown), good values (recovered.png), the Properties panel with
# advanced properties (properties_panel.png, in docs/usage.md), colouring by the displacement
# (colour.png), a long run with its progress (running.png) and after Abort (aborted.png).
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

# As a user would: Filters > Point Cloud (the 13th entry) > Point Cloud Bilateral Filter.
open_point_cloud_menu() {
  xdotool mousemove 193 10 click 1
  sleep 1
  for _ in $(seq 13); do xdotool key Down; sleep 0.1; done
  xdotool key Right
  sleep 1
}
open_point_cloud_menu
import -window root -crop 520x400+190+0 "$out/filters_menu.png"
xdotool key Return
sleep 2
set_field() {
  xdotool mousemove "$1" "$2" click --repeat 3 1
  xdotool type -- "$3"
  xdotool key Tab
  sleep 0.3
}
apply() {
  xdotool mousemove 48 508 click 1
  sleep "$1"
}
# The Output Messages window opens on the first message: out of the way of the panel.
move_messages() {
  local messages
  messages=$(xdotool search --name "^Output Messages$" | head -1 || true)
  [ -n "$messages" ] && xdotool windowmove "$messages" 700 620
  sleep 0.5
}

# Change values: first a bad radius (one error, an empty output)...
set_field 206 667 -0.05
apply 3
move_messages
import -window root "$out/error.png"
# ... then Radius 0 again: every parameter automatic (the defaults); the view shows the result.
set_field 206 667 0
apply 5
import -window root "$out/recovered.png"

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

# Colour by the displacement: tick Output Displacement Length, Apply, choose it in the toolbar's
# colour list (typing its first letter selects it).
xdotool mousemove 917 614 click 1
sleep 0.5
xdotool mousemove 970 101 click 1
sleep 5
xdotool mousemove 318 81 click 1
sleep 1
xdotool type D
xdotool key Return
sleep 2
import -window root "$out/colour.png"

# A long run (every point a neighbour of every other), then Abort, the red cross left of the
# progress bar.
xdotool mousemove 1220 319 click --repeat 3 1
xdotool type 1.5
xdotool key Tab
xdotool mousemove 970 101 click 1
sleep 3
import -window root "$out/running.png"
xdotool mousemove 500 984 click 1
sleep 2
import -window root "$out/aborted.png"
echo "wrote $out: filters_menu, error, recovered, properties_panel, colour, running, aborted"
