#!/bin/bash
# `mpirun -n 2 pathlab converge` on loopback (issue 17): with a sample budget the two ranks' run is
# the run of one process (every checkpoint at the same sample count, the same samples, rays and
# errors to rounding), its CSV saying how many ranks ran, also with a reference only rank 0 reads;
# with a time budget every checkpoint's samples are those of whole passes of both ranks;
# `mpirun -n 1` writes what one process writes; a rank that cannot load the scene stops the job
# within seconds with one line naming it; SIGINT leaves no output behind.
# Usage: mpi_converge_test.sh PATHLAB SOURCE_DIR MPIEXEC
. "$(dirname "$0")/../cli/cli_lib.sh"
. "$(dirname "$0")/mpi_lib.sh"
COMPARE="python3 $(dirname "$0")/compare_convergence_csv.py"
# One thread a rank: the splats of a pass are then summed in the same order as in one process.
# 13 spp: checkpoints at 1, 2, 3, 5, 8, 12, 13, where the ranks hold unequal shares.
small=(--width 16 --height 12 --seed 5 --threads 1 --max-length 4 --configs "bpt;pt" --spp 13 --reference-spp 30)

# compare WHAT ONE MANY RANKS: the CSVs agree as one process's and a RANKS-rank job's (see the script).
compare() {
  if out=$($COMPARE "$2" "$3" "$4" 2>&1); then ok; else fail "$1: $out"; fi
}

"$PATHLAB" converge "$BOX" -o "$TMP/one" "${small[@]}" >/dev/null 2>"$TMP/err" || fail "one process: $(cat "$TMP/err")"
if mpirun2 "$PATHLAB" converge "$BOX" -o "$TMP/two" "${small[@]}" >"$TMP/table" 2>"$TMP/err"; then
  compare "--spp, 2 ranks" "$TMP/one/convergence.csv" "$TMP/two/convergence.csv" 2
  grep -q "rendered by 2 MPI ranks" "$TMP/two/efficiency.md" && ok || fail "efficiency.md: $(cat "$TMP/two/efficiency.md")"
  grep -q "rendered by 2 MPI ranks" "$TMP/table" && ok || fail "the printed table: $(cat "$TMP/table")"
  grep -q "MPI ranks" "$TMP/one/efficiency.md" && fail "one process's efficiency.md names MPI ranks"
  [ "$(grep -c '^bpt: 13 spp (2 ranks)' "$TMP/err")" -eq 1 ] && ok || fail "not one bpt summary: $(cat "$TMP/err")"
  [ "$(grep -c 'reference: wrote' "$TMP/err")" -eq 1 ] && ok || fail "not one reference written: $(cat "$TMP/err")"
else fail "--spp, 2 ranks: $(cat "$TMP/err")"; fi

# A given reference is rank 0's to read: the image size is its, shared with rank 1. Against the
# reference the one process rendered, the job's CSV is again that process's.
REF=$(ls "$TMP"/one/reference-*.exr | head -1)
given=(--seed 5 --threads 1 --max-length 4 --configs "bpt;pt" --spp 13 --reference "$REF")
if mpirun2 "$PATHLAB" converge "$BOX" -o "$TMP/given" "${given[@]}" >/dev/null 2>"$TMP/err"; then
  compare "--reference, 2 ranks" "$TMP/one/convergence.csv" "$TMP/given/convergence.csv" 2
else fail "--reference, 2 ranks: $(cat "$TMP/err")"; fi

# One rank is the plain process: the same file but for the times.
if timeout 60 "$MPIEXEC" -n 1 "$PATHLAB" converge "$BOX" -o "$TMP/onerank" "${small[@]}" >/dev/null 2>"$TMP/err"; then
  compare "mpirun -n 1" "$TMP/one/convergence.csv" "$TMP/onerank/convergence.csv" 1
else fail "mpirun -n 1: $(cat "$TMP/err")"; fi

# --time: the ranks meet at every checkpoint, each having rendered whole passes of 16 x 12 samples.
if mpirun2 "$PATHLAB" converge "$BOX" -o "$TMP/timed" --width 16 --height 12 --threads 1 --max-length 4 \
    --configs "bpt;pt" --time 0.5 --reference-time 0.5 >/dev/null 2>"$TMP/err"; then
  python3 - "$TMP/timed/convergence.csv" <<'PY' && ok || fail "--time, 2 ranks: convergence.csv"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert {r["config"] for r in rows} == {"bpt", "pt"}, rows
for r in rows:
    assert r["ranks"] == "2", r
    assert int(r["camera_samples"]) == 16 * 12 * int(r["spp"]), r
for c in ("bpt", "pt"):
    mine = [r for r in rows if r["config"] == c]
    # The first checkpoint comes after one pass of each rank; the last at the budget.
    assert int(mine[0]["spp"]) == 2, mine[0]
    assert float(mine[-1]["seconds"]) >= 0.5, mine[-1]
    spp = [int(r["spp"]) for r in mine]
    assert spp == sorted(set(spp)), spp
PY
else fail "--time, 2 ranks: $(cat "$TMP/err")"; fi

# Rank 1 is given a scene that does not exist: the job stops at once, naming it; no output
# directory (rank 0 creates it only once every rank is ready).
stops_without_scene converge "$TMP/f" "${small[@]}"

# SIGINT to mpirun while the reference renders: the job ends (mpirun sees to that, killing ranks
# that linger), leaving neither results, nor a reference, nor a temporary in the output directory.
interrupted converge "$BOX" -o "$TMP/int" --width 16 --height 12 --threads 1 --time 60
[ -z "$(ls -A "$TMP/int" 2>/dev/null)" ] && ok || fail "SIGINT left output: $(ls -A "$TMP/int")"

# Metropolis runs over ranks in render only: one line from rank 0, a non-zero exit, no directory.
mpirun2 "$PATHLAB" converge "$BOX" -o "$TMP/mlt" --width 16 --height 12 --threads 1 --configs mlt --spp 2 \
  >/dev/null 2>"$TMP/err" </dev/null && fail "converge mlt under 2 ranks: exit code 0"
[ "$(grep -c "^pathlab: .*configuration 'mlt': Metropolis runs over MPI ranks in .pathlab render. only" "$TMP/err")" -eq 1 ] &&
  ok || fail "converge mlt under 2 ranks: $(cat "$TMP/err")"
[ -e "$TMP/mlt" ] && fail "converge mlt under 2 ranks left $TMP/mlt"
# Variance-aware MIS estimates its factors from one process's passes: refused the same way, by
# converge and by render.
mpirun2 "$PATHLAB" converge "$BOX" -o "$TMP/va" --width 16 --height 12 --threads 1 --configs "bpt:mis=variance-aware" \
  --spp 2 >/dev/null 2>"$TMP/err" </dev/null && fail "converge variance-aware under 2 ranks: exit code 0"
[ "$(grep -c "variance-aware MIS estimates its factors from one process" "$TMP/err")" -eq 1 ] &&
  ok || fail "converge variance-aware under 2 ranks: $(cat "$TMP/err")"
mpirun2 "$PATHLAB" render "$BOX" -o "$TMP/va.exr" --width 16 --height 12 --threads 1 --mis variance-aware --spp 2 \
  >/dev/null 2>"$TMP/err" </dev/null && fail "render variance-aware under 2 ranks: exit code 0"
[ "$(grep -c "variance-aware estimates its factors from one process" "$TMP/err")" -eq 1 ] && [ ! -e "$TMP/va.exr" ] &&
  ok || fail "render variance-aware under 2 ranks: $(cat "$TMP/err")"

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
