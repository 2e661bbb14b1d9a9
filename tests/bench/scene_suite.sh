#!/usr/bin/env bash
# The benchmark suite across scenes (issue 31): PT and BPT on every bundled scene against long
# references rendered once and cached outside the repository, at equal time (efficiency
# 1/(relMSE × s)) or at a fixed sample count (error per sample, relMSE × spp, which CPU load does
# not disturb); with a second binary, each scene runs on both, interleaved, and the table gives
# the ratios. Prints the table as Markdown on stdout:
#   tests/bench/scene_suite.sh [BIN=build/app/pathlab] [BASE_BIN] [OUT_DIR=out/suite]
# Environment (defaults in brackets):
#   SUITE_SCENES  [every assets/*.gltf]  scene names without .gltf
#   SUITE_TIME    [3]     seconds per configuration (equal time); SUITE_SPP, when set, renders
#                         that many samples per pixel instead (error per sample). The reference's
#                         own error adds to every relMSE: keep the spp well below SUITE_REF_SPP
#   SUITE_CONFIGS ["bpt;pt"]  `pathlab converge --configs`
#   SUITE_WIDTH   [128]   image width (the height follows the camera's aspect)
#   SUITE_MAX_LENGTH [10] maximum path length in edges
#   SUITE_REF_SPP [1024]  samples per pixel of a reference (bpt, the binary BIN)
#   SUITE_REFS    [${XDG_CACHE_HOME:-$HOME/.cache}/pathlab/references]  the reference cache
#   REF_SEED      [20261207]  the references' seed (never the configurations', 0)
#   SUITE_ARGS    []      more `pathlab converge` options for both binaries, e.g. "--threads 1 --clock cpu"
#   BASE_ARGS     [$SUITE_ARGS]  options of the BASE_BIN runs (e.g. "--no-rr" against the same binary)
set -euo pipefail
SRC=$(cd "$(dirname "$0")/../.." && pwd)
BIN=${1:-$SRC/build/app/pathlab}
BASE_BIN=${2:-}
OUT=${3:-$SRC/out/suite}
SUITE_SCENES=${SUITE_SCENES:-$(cd "$SRC/assets" && ls *.gltf | sed 's/\.gltf$//')}
SUITE_TIME=${SUITE_TIME:-3}
SUITE_SPP=${SUITE_SPP:-}
SUITE_CONFIGS=${SUITE_CONFIGS:-bpt;pt}
SUITE_WIDTH=${SUITE_WIDTH:-128}
SUITE_MAX_LENGTH=${SUITE_MAX_LENGTH:-10}
SUITE_REF_SPP=${SUITE_REF_SPP:-1024}
SUITE_REFS=${SUITE_REFS:-${XDG_CACHE_HOME:-$HOME/.cache}/pathlab/references}
SUITE_ARGS=${SUITE_ARGS:-}
BASE_ARGS=${BASE_ARGS-$SUITE_ARGS}
mkdir -p "$OUT" "$SUITE_REFS"
budget=(--time "$SUITE_TIME")
[ -n "$SUITE_SPP" ] && budget=(--spp "$SUITE_SPP")

# A reference is keyed by the scene file's content and the image's settings, so an edited scene
# gets a new one; the estimator's changes do not (every estimator has the same expectation). Its
# seed is not the configurations' (converge's default 0): with the same seed a bpt configuration
# would draw the reference's own first samples, and its error would be measured against itself
# (sessions before 25 did; the 1024-spp bpt rows of a scene then read near zero).
REF_SEED=${REF_SEED:-20261207}
reference() {
  local scene=$1 hash ref
  hash=$(sha256sum "$SRC/assets/$scene.gltf" | cut -c1-12)
  ref="$SUITE_REFS/$scene-$hash-w$SUITE_WIDTH-l$SUITE_MAX_LENGTH-spp$SUITE_REF_SPP-seed$REF_SEED.exr"
  if [ ! -f "$ref" ]; then
    "$BIN" render "$SRC/assets/$scene.gltf" -o "$ref.tmp.exr" --spp "$SUITE_REF_SPP" --width "$SUITE_WIDTH" --seed "$REF_SEED" \
      --max-length "$SUITE_MAX_LENGTH" --force 2>"$OUT/reference-$scene.log" </dev/null
    mv "$ref.tmp.exr" "$ref"
  fi
  echo "$ref"
}

run() {  # run NAME BIN ARGS... : one converge of every configuration into OUT/NAME
  local name=$1 bin=$2
  shift 2
  "$bin" converge "$SRC/assets/$scene.gltf" -o "$OUT/$name" --reference "$ref" --configs "$SUITE_CONFIGS" \
    --max-length "$SUITE_MAX_LENGTH" "${budget[@]}" --force "$@" >"$OUT/$name.log" 2>&1 </dev/null
}

echo "Load average before: $(cut -d' ' -f1-3 /proc/loadavg). Budget: ${budget[*]}, width $SUITE_WIDTH, max length $SUITE_MAX_LENGTH, references $SUITE_REF_SPP spp (bpt)."
echo
dirs=()
for scene in $SUITE_SCENES; do
  ref=$(reference "$scene")
  # shellcheck disable=SC2086
  run "new-$scene" "$BIN" $SUITE_ARGS
  dirs+=("$scene=$OUT/new-$scene")
  if [ -n "$BASE_BIN" ]; then
    # shellcheck disable=SC2086
    run "base-$scene" "$BASE_BIN" $BASE_ARGS
    dirs[-1]+=",$OUT/base-$scene"
  fi
done
python3 "$SRC/tests/bench/scene_suite_table.py" "${dirs[@]}"
echo
echo "Load average after: $(cut -d' ' -f1-3 /proc/loadavg)."
