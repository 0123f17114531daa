#!/bin/bash
# pcb_scale.sh: the benchmark for scale (docs/scale.md). Generates LiDAR-like tiles of each size
# (pcb_benchmark --write-lidar, never in memory whole), then runs pcbilateral on each: in memory
# where the cloud fits, streamed with each --memory-limit, and under mpirun (2 processes, one
# thread each) where the pieces fit; one line per run: wall time, peak resident memory of each
# process, points per second per core, and whether the output has the in-memory run's bytes.
# Run by hand from the source tree, after a build; never by the tests (but --self-test).
#
#   Testing/Benchmark/pcb_scale.sh [--build build] [--work DIR] [--sizes "20000000 60000000"]
#       [--limits "1G 2G 4G"] [--formats "las laz"] [--modes "memory stream mpi"]
#       [--priority] [--keep]
#   Testing/Benchmark/pcb_scale.sh --self-test --build build    (small counts, a few seconds)
#
# --priority runs every measurement in its own session at autogroup nice -10 (as root: see
# docs/speed.md "Scheduling"). The big files go to --work (default: a folder under /tmp; not
# /dev/shm) and are deleted at the end unless --keep.
set -u
build=build
work=
sizes="20000000 60000000 200000000"
limits="1G 2G 4G"
formats="las laz"
modes="memory stream mpi"
priority=0
keep=0
selftest=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --sizes) sizes=$2; shift 2 ;;
    --limits) limits=$2; shift 2 ;;
    --formats) formats=$2; shift 2 ;;
    --modes) modes=$2; shift 2 ;;
    --priority) priority=1; shift ;;
    --keep) keep=1; shift ;;
    --self-test) selftest=1; shift ;;
    *) echo "usage: see the head of $0" >&2; exit 2 ;;
  esac
done
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "$build" && pwd) || { echo "error: no build folder $build" >&2; exit 2; }
bench=$build/bin/pcb_benchmark
cli=$build/bin/pcbilateral
for program in "$bench" "$cli"; do
  [ -x "$program" ] || { echo "error: $program is not built" >&2; exit 2; }
done
if [ -z "$work" ]; then
  work=$(mktemp -d /tmp/pcb_scale.XXXXXX)
else
  mkdir -p "$work"
fi
cleanup() { [ "$keep" = 1 ] || rm -rf "$work"; }
trap cleanup EXIT
params="-r 3.6 -n 0.5 -N 2"
bytes_per_point=153 # pcbilateral's peak in memory (docs/streaming.md)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# The command in its own session with priority when asked, its peak memory (KB) into $1; without
# GNU time (Debian's package time), the peak is not measured.
measured() {
  local peak=$1
  shift
  local timed=(/usr/bin/time -f %M -o "$peak")
  [ -x /usr/bin/time ] || { : > "$peak"; timed=(); }
  if [ "$priority" = 1 ]; then
    setsid -w bash -c 'echo -10 > /proc/self/autogroup && exec "$@"' prioritised "${timed[@]}" "$@"
  else
    "${timed[@]}" "$@"
  fi
}

seconds_since() { awk -v start="$1" -v end="$(date +%s.%N)" 'BEGIN { printf "%.1f", end - start }'; }

available_kb() { awk '/MemAvailable/ { print $2 }' /proc/meminfo; }

# One table row: size, format, run, seconds, peaks (MB), points/s/core, same bytes.
report() {
  local points=$1 format=$2 run=$3 seconds=$4 peaks=$5 cores=$6 same=$7
  local rate
  rate=$(awk -v p="$points" -v s="$seconds" -v c="$cores" 'BEGIN { printf "%.0f", p / s / c }')
  printf "| %s | %s | %s | %s s | %s | %s | %s |\n" "$points" "$format" "$run" "$seconds" \
    "$peaks" "$rate" "$same"
}

compare() { # the output against the in-memory one, when there is one
  if [ -f "$2" ]; then cmp -s "$1" "$2" && echo same || echo DIFFERENT; else echo "-"; fi
}

peak_mb() { awk '{ printf "%.0f MB", $1 / 1024; found = 1 } END { if (!found) print "-" }' "$1"; }

run_memory() {
  local points=$1 format=$2 input=$3 reference=$4
  local need=$((points * bytes_per_point / 1024))
  if [ "$need" -gt "$(( $(available_kb) * 9 / 10 ))" ]; then
    echo "| $points | $format | in memory | needs ~$((need / 1024)) MB, more than is available: not run | | | |"
    return
  fi
  local start
  start=$(date +%s.%N)
  measured "$work/peak" "$cli" "$input" "$reference" $params -t 2 > "$work/log" 2>&1 ||
    { echo "| $points | $format | in memory | failed: $(tail -1 "$work/log") | | | |"; return; }
  report "$points" "$format" "in memory" "$(seconds_since "$start")" \
    "$(peak_mb "$work/peak")" 2 "-"
}

run_stream() {
  local points=$1 format=$2 input=$3 reference=$4 limit=$5 out=$work/streamed.las
  local start
  start=$(date +%s.%N)
  measured "$work/peak" "$cli" "$input" "$out" $params -t 2 --memory-limit "$limit" \
    > "$work/log" 2>&1 ||
    { echo "| $points | $format | --memory-limit $limit | failed: $(tail -1 "$work/log") | | | |"; return; }
  local elapsed
  elapsed=$(seconds_since "$start")
  # Without an in-memory run, the streamed runs are compared with the first of them.
  local against=$reference
  [ -f "$reference" ] || against=$work/first-streamed.las
  local same
  same=$(compare "$out" "$against")
  [ -f "$reference" ] || [ "$same" = "-" ] || same="$same as the first limit's"
  report "$points" "$format" "--memory-limit $limit" "$elapsed" "$(peak_mb "$work/peak")" 2 "$same"
  if [ ! -f "$reference" ] && [ ! -f "$against" ]; then mv "$out" "$against"; else rm -f "$out"; fi
}

# Two processes of one thread; each process's peak from its own /usr/bin/time.
run_mpi() {
  local points=$1 format=$2 input=$3 reference=$4 out=$work/mpi.las
  # A process holds its half and the halo, about twice the in-memory bytes per point (docs/scale.md).
  local need=$((points * bytes_per_point * 2 / 1024))
  if [ "$need" -gt "$(( $(available_kb) * 8 / 10 ))" ]; then
    echo "| $points | $format | mpirun -np 2 | needs ~$((need / 1024)) MB, more than is available: not run | | | |"
    return
  fi
  rm -f "$work"/peak.rank*
  local start
  start=$(date +%s.%N)
  local rank_cmd="exec /usr/bin/time -f %M -o $work/peak.rank\$OMPI_COMM_WORLD_RANK pvbatch \
    $source_dir/Examples/Python/denoise_mpi.py $input $out --radius 3.6 --normal-radius 0.5 \
    --iterations 2 --threads 1 \
    $(ls "$build"/lib/paraview-*/plugins/PointCloudBilateral/PointCloudBilateral.so 2>/dev/null |
      head -1 | sed 's/^/--plugin /')"
  local mpi=(mpirun -np 2 --bind-to none sh -c "$rank_cmd")
  if [ "$priority" = 1 ]; then
    setsid -w bash -c 'echo -10 > /proc/self/autogroup && exec "$@"' prioritised "${mpi[@]}" \
      > "$work/log" 2>&1
  else
    "${mpi[@]}" > "$work/log" 2>&1
  fi || { echo "| $points | $format | mpirun -np 2 | failed: $(tail -1 "$work/log") | | | |"; return; }
  report "$points" "$format" "mpirun -np 2" "$(seconds_since "$start")" \
    "$(peak_mb "$work/peak.rank0"), $(peak_mb "$work/peak.rank1")" 2 \
    "$(compare "$out" "$reference")"
  rm -f "$out"
}

if [ "$selftest" = 1 ]; then
  # The generator's tile reads back, and a streamed run gives the in-memory run's bytes.
  sizes=60000 limits="200M 300M" formats="las laz" modes="memory stream"
  export PCB_STREAMING_SLAB_POINTS=20000
fi

echo "| points | input | run | time | peak per process | points/s/core | bytes as in memory |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
status=0
for points in $sizes; do
  for format in $formats; do
    input=$work/lidar$points.$format
    reference=$work/memory$points.las
    start=$(date +%s.%N)
    measured "$work/peak" "$bench" --write-lidar "$points" "$input" > "$work/log" 2>&1 ||
      { echo "error: $(cat "$work/log")" >&2; exit 1; }
    echo "| $points | $format | generated ($(du -m "$input" | cut -f1) MB) | $(seconds_since "$start") s | $(peak_mb "$work/peak") | | |"
    rm -f "$reference"
    for mode in $modes; do
      case "$mode" in
        memory) run_memory "$points" "$format" "$input" "$reference" ;;
        stream) for limit in $limits; do
                  run_stream "$points" "$format" "$input" "$reference" "$limit"
                done ;;
        mpi) run_mpi "$points" "$format" "$input" "$reference" ;;
      esac
    done
    rm -f "$input" "$reference" "$work/first-streamed.las"
  done
done | tee "$work/table"
if [ "$selftest" = 1 ]; then
  grep -q DIFFERENT "$work/table" && status=1
  grep -q failed "$work/table" && status=1
  [ "$(grep -c same "$work/table")" = 4 ] || status=1
fi
exit $status
