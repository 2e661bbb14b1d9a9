# Shared by the MPI tests (sourced after cli_lib.sh): MPIEXEC, the environment Open MPI needs in
# CI, a 2-rank launcher, the check that a rank without its scene stops the job, and a job
# interrupted.
MPIEXEC=$3
BOX="$SRC/assets/cornell-box.gltf"
# CI runs as root; Open MPI refuses to without these. Shared memory without ptrace (containers).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
mpirun2() { timeout 120 "$MPIEXEC" -n 2 --oversubscribe "$@"; }

# stops_without_scene COMMAND OUTPUT ARGS...: rank 0 runs `pathlab COMMAND BOX -o OUTPUT ARGS...`,
# rank 1 the same with a scene that does not exist. One line from pathlab naming rank 1 and the
# file, a non-zero exit within seconds (no rank left waiting in a collective), no OUTPUT.
stops_without_scene() {
  local command=$1 output=$2
  shift 2
  local begin code took
  begin=$(date +%s)
  timeout 30 "$MPIEXEC" -n 1 "$PATHLAB" "$command" "$BOX" -o "$output" "$@" : \
    -n 1 "$PATHLAB" "$command" "$TMP/missing.gltf" -o "$output" "$@" >"$TMP/out" 2>"$TMP/err" </dev/null
  code=$?
  took=$(( $(date +%s) - begin ))
  [ "$code" -ne 0 ] && [ "$code" -ne 124 ] && ok || fail "$command, missing scene on rank 1: exit code $code"
  [ "$took" -le 10 ] && ok || fail "$command, missing scene on rank 1: $took s to stop"
  grep -qE "^pathlab: rank 1 of 2: .*missing.gltf" "$TMP/err" && ok ||
    fail "$command, missing scene: no line naming rank 1: $(cat "$TMP/err")"
  [ "$(grep -c '^pathlab:' "$TMP/err")" -eq 1 ] && ok || fail "$command, missing scene: not one line: $(cat "$TMP/err")"
  [ -e "$output" ] && fail "$command, missing scene: $output was written"
}

# interrupted ARGS...: `pathlab ARGS...` on 2 ranks gets SIGINT (to mpirun) after 3 s and must
# have ended 10 s later; what it left behind is the caller's to check.
interrupted() {
  "$MPIEXEC" -n 2 --oversubscribe "$PATHLAB" "$@" >/dev/null 2>"$TMP/err" &
  local job=$!
  sleep 3
  kill -INT "$job"
  for _ in $(seq 50); do kill -0 "$job" 2>/dev/null || break; sleep 0.2; done
  if kill -0 "$job" 2>/dev/null; then fail "SIGINT: the job still runs after 10 s"; kill -KILL "$job"; else ok; fi
  wait "$job" 2>/dev/null
}
