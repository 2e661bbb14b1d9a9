#!/usr/bin/env bash
# Runs every measurement of docs/benchmarks.md and prints its tables as Markdown on stdout (and
# writes the raw data and converge outputs to OUT_DIR). Run it on a quiet machine:
#   tests/bench/run_benchmarks.sh [BUILD_DIR=build] [OUT_DIR=out/bench]
# Environment (defaults in brackets):
#   BENCH_MIN_TIME [1]     seconds per benchmark repetition; BENCH_REPS [3] repetitions (median kept)
#   BENCH_FILTER   [.]     regex of benchmarks to run
#   CONVERGE_SCENES ["cornell-box bidir-lamp caustic veach-mis"]  scenes for `pathlab converge` ("" skips)
#   CONVERGE_TIME  [20]    seconds per configuration; the reference gets 10 times as long
#   CONVERGE_SIZE  [128]   image side in pixels
#   CONVERGE_ARGS  []      more `pathlab converge` options, e.g. "--threads 1 --clock cpu" on a loaded machine
#   RUN_BENCH      [1]     0 skips pathlab_bench (converge only)
set -euo pipefail
SRC=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$SRC/build}
OUT=${2:-$SRC/out/bench}
BENCH_MIN_TIME=${BENCH_MIN_TIME:-1}
BENCH_REPS=${BENCH_REPS:-3}
BENCH_FILTER=${BENCH_FILTER:-.}
CONVERGE_SCENES=${CONVERGE_SCENES-cornell-box bidir-lamp caustic veach-mis}
CONVERGE_TIME=${CONVERGE_TIME:-20}
CONVERGE_SIZE=${CONVERGE_SIZE:-128}
CONVERGE_ARGS=${CONVERGE_ARGS:-}
RUN_BENCH=${RUN_BENCH:-1}
# PT and LT, BPT under each heuristic, and one instructive subset: the unidirectional techniques
# only (s = 0 hits, s = 1 next-event estimation, t = 1 light tracing), i.e. BPT without the
# connections of two subpaths that each have a scattering vertex.
CONFIGS=${CONFIGS:-"bpt;pt;lt;bpt:mis=power;bpt:mis=uniform;bpt:techniques=s=0;s=1;t=1"}
mkdir -p "$OUT"
loadavg() { cut -d' ' -f1-3 /proc/loadavg; }

echo "## Machine"
echo
echo "- CPU: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) vCPUs ($(lscpu | sed -n 's/^Hypervisor vendor: *//p') guest), L3 $(lscpu | sed -n 's/^L3 cache: *//p')"
echo "- Memory: $(free -g | awk '/^Mem:/ {print $2}') GiB; $(. /etc/os-release && echo "$PRETTY_NAME"); $(g++ --version | head -1)"
echo "- Commit: $(git -C "$SRC" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$SRC" diff --quiet 2>/dev/null || echo ' (with uncommitted changes)')"
echo

if [ "$RUN_BENCH" != 0 ]; then
  echo "## Throughput and the ray-tracing ceiling"
  echo
  echo "Load average before the benchmarks: $(loadavg)."
  echo
  "$BUILD/tests/bench/pathlab_bench" --benchmark_filter="$BENCH_FILTER" --benchmark_min_time="$BENCH_MIN_TIME" \
    --benchmark_repetitions="$BENCH_REPS" --benchmark_report_aggregates_only=true \
    --benchmark_out="$OUT/bench.json" --benchmark_out_format=json >"$OUT/bench.txt" 2>&1
  python3 "$SRC/tests/bench/bench_report.py" "$OUT/bench.json"
  echo
  echo "Load average after the benchmarks: $(loadavg)."
fi

for scene in $CONVERGE_SCENES; do
  echo
  echo "## \`pathlab converge\`: $scene (--time $CONVERGE_TIME --width $CONVERGE_SIZE --height $CONVERGE_SIZE $CONVERGE_ARGS)"
  echo
  echo "Load average before: $(loadavg)."
  echo
  "$BUILD/app/pathlab" converge "$SRC/assets/$scene.gltf" -o "$OUT/converge-$scene" --configs "$CONFIGS" \
    --time "$CONVERGE_TIME" --width "$CONVERGE_SIZE" --height "$CONVERGE_SIZE" --force $CONVERGE_ARGS \
    >"$OUT/converge-$scene.md" 2>"$OUT/converge-$scene.log" </dev/null
  cat "$OUT/converge-$scene/efficiency.md"
  echo
  echo "Load average after: $(loadavg). Plot: \`$OUT/converge-$scene/convergence.svg\`."
done
