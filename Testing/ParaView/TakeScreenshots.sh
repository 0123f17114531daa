#!/usr/bin/env bash
# Takes the screenshots of the ParaView GUI with the plugin that the docs show
# (Plugin/Screenshots/), and a few more for a look at the GUI's states:
#   filters_menu.png      Filters > Point Cloud > Point Cloud Bilateral Filter
#   properties_panel.png  the Properties panel, advanced properties shown, after the filter ran
#                         with its automatic parameters on a real scan (its chosen and measured
#                         values)
#   before_after.png      a real scan and the filter's output side by side, one camera
#   open_dialog.png       File > Open on a folder of LAS, LAZ and PCD files
#   colour.png, error.png, running.png, aborted.png (not in the docs): coloured by the
#                         displacement, a bad radius's error, a long run, and after Abort
#   Testing/ParaView/TakeScreenshots.sh BUILD_DIR OUTPUT_DIR [REAL_DATA_DIR]
# (PCB_XVFB_DISPLAY=:N picks the X display it starts; otherwise a random one.)
# REAL_DATA_DIR holds the real scans (default /work/shared/data/real; see its README.md).
# Each screenshot has a ParaView session of its own, set up from Python
# (ScreenshotSession.py), so the few clicks left are on places that do not move when the
# Properties panel grows: the menu bar, keyboard shortcuts, the floating panel's own header,
# the status bar. A session that dies on the known intermittent X errors of ParaView 5.11
# under Xvfb is started again (three times at most).
# Needs xvfb, xdotool, imagemagick and libqt5svg5 (for the icons). Starts its own X server and
# ParaView, and ends only those.
set -euo pipefail
build=$(cd "$1" && pwd)
mkdir -p "$2"
out=$(cd "$2" && pwd)
real=${3:-/work/shared/data/real}
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
for tool in Xvfb xdotool import; do
  command -v "$tool" > /dev/null || {
    echo "missing $tool: apt-get install xvfb xdotool imagemagick libqt5svg5" >&2; exit 1; }
done
plugin_dir=$(dirname "$(find "$build" -name PointCloudBilateral.so -print -quit)")

display=${PCB_XVFB_DISPLAY:-:$((RANDOM % 400 + 100))}
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

# start_session SHOT [VARIABLE=VALUE...]: ParaView with ScreenshotSession.py for SHOT, its
# window at 0,0 and 1500x1000, the welcome dialog closed, once the session's set-up is done.
start_session() {
  local shot=$1 attempt ready=$out/.ready main
  shift
  for attempt in 1 2 3; do
    rm -f "$ready"
    env PCB_SHOT="$shot" PCB_READY="$ready" PCB_SOURCE_DIR="$source_dir" \
      PV_PLUGIN_PATH="$plugin_dir" "$@" \
      paraview --dr "--script=$source_dir/Testing/ParaView/ScreenshotSession.py" \
      > "$out/paraview-$shot.log" 2>&1 &
    paraview_pid=$!
    for _ in $(seq 1200); do
      { [ -e "$ready" ] || ! kill -0 "$paraview_pid" 2> /dev/null; } && break
      sleep 0.1
    done
    if [ -e "$ready" ] && kill -0 "$paraview_pid" 2> /dev/null; then
      sleep 1
      local welcome
      welcome=$(xdotool search --name "^Welcome to ParaView" 2> /dev/null | head -1 || true)
      [ -n "$welcome" ] && xdotool windowactivate --sync "$welcome" key Escape 2> /dev/null || true
      xdotool key Escape
      main=$(xdotool search --name "ParaView 5" | head -1)
      xdotool windowsize "$main" 1500 1000
      xdotool windowmove "$main" 0 0
      sleep 2
      return 0
    fi
    stop_session
    grep -q -E "bad X server connection|X Error" "$out/paraview-$shot.log" || break
    echo "TakeScreenshots.sh: the $shot session lost its X server (run $attempt); again" >&2
  done
  echo "TakeScreenshots.sh: the $shot session did not start; see $out/paraview-$shot.log" >&2
  exit 1
}
stop_session() {
  [ -n "$paraview_pid" ] && kill "$paraview_pid" 2> /dev/null || true
  [ -n "$paraview_pid" ] && wait "$paraview_pid" 2> /dev/null || true
  paraview_pid=
  sleep 0.5
}

# The Filters menu (the menu bar's fifth title), then Point Cloud, the category the filter's
# XML names: ParaView 5.11's 13th entry.
start_session menu
xdotool mousemove 216 10 click 1
sleep 1
for _ in $(seq 13); do xdotool key Down; sleep 0.1; done
xdotool key Right
sleep 1
import -window root -crop 520x400+190+0 "$out/filters_menu.png"
stop_session

# The Properties panel after a run with every parameter automatic, advanced properties shown:
# the panel floated (its dock's title bar double-clicked, found as the "Properties" tab's dock
# title), made tall and wide enough, and its gear button (right of its search box) pressed.
start_session panel PCB_SCAN="$real/room_scan2.ply"
# The dock's title bar is the first line of text "Properties" under the Properties/Information
# tabs: left column, just below the tabs at 63 % of the default layout's height.
xdotool mousemove 37 477 click --repeat 2 --delay 80 1
sleep 1.5
panel=$(xdotool search --name "^Properties$" | head -1 || true)
if [ -z "$panel" ]; then
  echo "TakeScreenshots.sh: the Properties dock did not float" >&2
  exit 1
fi
xdotool windowsize "$panel" 520 940
xdotool windowmove "$panel" 900 40
sleep 1.5
eval "$(xdotool getwindowgeometry --shell "$panel")"
xdotool mousemove $((X + WIDTH - 23)) $((Y + 72)) click 1
sleep 1.5
import -window "$panel" "$out/properties_panel.png"
stop_session

# Before and after on a real scan: a Kinect-like depth frame seen from above (the depth runs
# up the picture), input left, output right: the frame's depth steps (the sensor's quantization,
# rows of points parallel to the image plane) become the floor and the objects they sample. The
# crop is the two views, under their toolbars.
start_session beforeafter PCB_SCAN="$real/kinect_capture0001.ply" PCB_POINT_RADIUS=0.002 \
  PCB_CAMERA="-0.05 7.4 2.33 -0.05 -0.2 2.33 0 0 -1"
import -window root -crop 1193x767+302+198 "$out/before_after.png"
stop_session

# File > Open on a folder of LAS, LAZ and PCD files (links to the shared samples
# beside REAL_DATA_DIR: ../las, ../laz, ../pcd).
files=$out/files
rm -rf "$files"
mkdir -p "$files"
for sample in las/autzen_trim.las las/1.2-with-color.las laz/autzen_trim.laz \
  laz/1.2-with-color.copc.laz pcd/milk.pcd pcd/lamppost.pcd; do
  [ -e "$real/../$sample" ] && ln -s "$(cd "$real/.." && pwd)/$sample" "$files/"
done
start_session dialog
xdotool mousemove 28 41 click 1 # the toolbar's first button, Open
sleep 2
dialog=$(xdotool search --name "^Open File" | head -1)
xdotool type --delay 20 "$files/"
xdotool key Return
sleep 1.5
import -window "$dialog" "$out/open_dialog.png"
stop_session

# Coloured by the displacement, and a bad radius's error (set up from Python).
start_session colour
import -window root "$out/colour.png"
stop_session
start_session error
import -window root "$out/error.png"
stop_session

# A long run (every point a neighbour of every other), then Abort: the red cross left of the
# progress bar, a third of the way along the status bar (as ParaView.gui-abort clicks it).
start_session running
sleep 2
import -window root "$out/running.png"
eval "$(xdotool search --name "ParaView 5" getwindowgeometry --shell | head -5)"
xdotool mousemove $((X + WIDTH / 3)) $((Y + HEIGHT - 13)) click 1
sleep 2
import -window root "$out/aborted.png"
stop_session
rm -f "$out/.ready"
echo "wrote $out: filters_menu, properties_panel, before_after, open_dialog, colour, error," \
  "running, aborted"
