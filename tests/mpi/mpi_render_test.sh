#!/bin/bash
# `mpirun -n 2 pathlab render` on loopback (issue 17): two ranks of P passes each give the image of
# one process rendering 2P passes with the same seed, to 1e-6 relative per pixel (the same samples,
# added in another order), for the path tracer and for BPT with its light-tracing splats and the
# technique pyramid, and for Metropolis (the ranks split the chains); `mpirun -n 1` is the plain
# process bit for bit; a rank that cannot load the
# scene stops the job within seconds with one line naming it; SIGINT leaves no output behind.
# Usage: mpi_render_test.sh PATHLAB SOURCE_DIR MPIEXEC
. "$(dirname "$0")/../cli/cli_lib.sh"
. "$(dirname "$0")/mpi_lib.sh"
COMPARE="python3 $(dirname "$0")/compare_pfm.py"
# One thread a rank: the splats of a pass are then summed in the same order as in one process.
small=(--width 24 --height 16 --seed 9 --threads 1 --max-length 4)

# compare NAME A1 B1 [A2 B2 ...]: each pair of PFM files holds the same values to 1e-6 relative.
compare() {
  local what=$1
  shift
  if out=$($COMPARE "$@" 2>&1); then ok; else fail "$what: $out"; fi
}

# Path tracer: 2 ranks x 3 passes against 6 passes.
"$PATHLAB" render "$BOX" -o "$TMP/pt1.pfm" "${small[@]}" --integrator pt --spp 6 2>"$TMP/err" || fail "pt, one process: $(cat "$TMP/err")"
if mpirun2 "$PATHLAB" render "$BOX" -o "$TMP/pt2.pfm" "${small[@]}" --integrator pt --spp 6 2>"$TMP/err"; then
  compare "pt, 2 ranks" "$TMP/pt1.pfm" "$TMP/pt2.pfm"
  grep -q "pt2.pfm: 6 spp (pt, 2 ranks)" "$TMP/err" && ok || fail "pt summary: $(cat "$TMP/err")"
  [ "$(grep -c 'pt2.pfm: 6 spp' "$TMP/err")" -eq 1 ] && ok || fail "not one summary: $(cat "$TMP/err")"
  [ "$(grep -c 'loaded in' "$TMP/err")" -eq 1 ] && ok || fail "the load line more than once: $(cat "$TMP/err")"
else fail "pt, 2 ranks: $(cat "$TMP/err")"; fi

# BPT (camera sums and splats) with the pyramid, and an odd count: 5 = 3 passes + 2 passes.
"$PATHLAB" render "$BOX" -o "$TMP/b1.pfm" "${small[@]}" --spp 5 --pyramid 3 2>"$TMP/err" || fail "bpt, one process: $(cat "$TMP/err")"
if mpirun2 "$PATHLAB" render "$BOX" -o "$TMP/b2.pfm" "${small[@]}" --spp 5 --pyramid 3 2>"$TMP/err"; then
  pairs=("$TMP/b1.pfm" "$TMP/b2.pfm")
  for one in "$TMP"/b1-s*.pfm; do pairs+=("$one" "${one/b1-/b2-}"); done
  # 9 techniques up to length 3, weighted and unweighted, and the image.
  [ "${#pairs[@]}" -eq 38 ] && ok || fail "pyramid: $(( ${#pairs[@]} / 2 - 1 )) technique images, not 18"
  compare "bpt and its pyramid, 2 ranks" "${pairs[@]}"
  [ -s "$TMP/b2-pyramid.png" ] && ok || fail "no pyramid mosaic"
  grep -q "b2.pfm: 5 spp (bpt, 2 ranks)" "$TMP/err" && ok || fail "bpt summary: $(cat "$TMP/err")"
else fail "bpt, 2 ranks: $(cat "$TMP/err")"; fi

# Metropolis (issue 33): the ranks pool their bootstrap samples and split the chains; every rank
# runs every pass with its share of the mutations (and rank p mod 2 the direct image's pass p), so
# two ranks give one process's image to 1e-6 and make as many proposals, not twice as many.
mlt=(--integrator mlt --chains 40 --bootstrap 2000 --spp 5)
for variant in "mmlt" "pss" "mmlt --mlt-direct 2"; do
  name=${variant// /}
  # shellcheck disable=SC2086
  "$PATHLAB" render "$BOX" -o "$TMP/m1$name.pfm" "${small[@]}" "${mlt[@]}" --mlt-variant $variant 2>"$TMP/err1" ||
    fail "mlt $variant, one process: $(cat "$TMP/err1")"
  # shellcheck disable=SC2086
  if mpirun2 "$PATHLAB" render "$BOX" -o "$TMP/m2$name.pfm" "${small[@]}" "${mlt[@]}" --mlt-variant $variant 2>"$TMP/err"; then
    compare "mlt $variant, 2 ranks" "$TMP/m1$name.pfm" "$TMP/m2$name.pfm"
    grep -q "m2$name.pfm: 5 spp (mlt, 2 ranks)" "$TMP/err" && ok || fail "mlt $variant summary: $(cat "$TMP/err")"
    one=$(grep -o "[0-9]* proposals" "$TMP/err1") two=$(grep -o "[0-9]* proposals" "$TMP/err")
    [ -n "$one" ] && [ "$one" = "$two" ] && ok || fail "mlt $variant: '$one' in one process, '$two' in 2 ranks"
  else fail "mlt $variant, 2 ranks: $(cat "$TMP/err")"; fi
done
mpirun2 "$PATHLAB" render "$BOX" -o "$TMP/mt.pfm" "${small[@]}" --integrator mlt --chains 40 --bootstrap 2000 --time 0.5 \
  2>"$TMP/err" && [ -s "$TMP/mt.pfm" ] && ok || fail "mlt --time under 2 ranks: $(cat "$TMP/err")"

# The same job under one rank is the plain process, bit for bit.
if timeout 60 "$MPIEXEC" -n 1 "$PATHLAB" render "$BOX" -o "$TMP/b1rank.pfm" "${small[@]}" --spp 5 2>"$TMP/err"; then
  cmp -s "$TMP/b1.pfm" "$TMP/b1rank.pfm" && ok || fail "mpirun -n 1 differs from one process"
else fail "mpirun -n 1: $(cat "$TMP/err")"; fi

# --time: every rank stops at T, the leader writes the image.
mpirun2 "$PATHLAB" render "$BOX" -o "$TMP/t.pfm" "${small[@]}" --time 0.5 2>"$TMP/err" && [ -s "$TMP/t.pfm" ] && ok ||
  fail "--time under 2 ranks: $(cat "$TMP/err")"

# Rank 1 is given a scene that does not exist: the job stops at once, naming it; no image.
stops_without_scene render "$TMP/f.pfm" "${small[@]}" --spp 2

# Only render and converge run as a job.
mpirun2 "$PATHLAB" check "$BOX" >"$TMP/out" 2>"$TMP/err" </dev/null && fail "check under 2 ranks: exit code 0"
[ "$(grep -c '^pathlab: only render and converge run as an MPI job' "$TMP/err")" -eq 1 ] && ok || fail "check under 2 ranks: $(cat "$TMP/err")"

# SIGINT to mpirun during a render: the job ends, and neither the image nor a temporary is left.
interrupted render "$BOX" -o "$TMP/int.pfm" "${small[@]}" --time 60
ls -a "$TMP" | grep -qE '^int\.pfm$|^\.int\.pfm\.tmp' && fail "SIGINT left output: $(ls -a "$TMP")" || ok

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
