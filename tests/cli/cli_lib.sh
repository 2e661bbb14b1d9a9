# Shared by the end-to-end CLI tests (sourced): PATHLAB, SRC, a scratch TMP removed on exit, and
# the pass/fail bookkeeping with expect_error.
set -u
PATHLAB=$1
SRC=$2
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
failures=0
passes=0

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { passes=$((passes + 1)); }

# expect_error DESCRIPTION PATTERN ARGS...: non-zero exit, exactly one line on stderr matching PATTERN
expect_error() {
  local what=$1 pattern=$2
  shift 2
  # A deadline, so that a refusal that hangs (a FIFO, a decoder looping) fails instead of stalling ctest.
  timeout "${CLI_DEADLINE:-120}" "$PATHLAB" "$@" >"$TMP/out" 2>"$TMP/err" </dev/null
  local code=$?
  if [ "$code" -eq 124 ]; then fail "$what: still running after ${CLI_DEADLINE:-120} s (hung)"; return; fi
  if [ "$code" -eq 0 ]; then fail "$what: exit code 0"; return; fi
  if [ "$code" -gt 128 ]; then fail "$what: crashed with code $code"; return; fi
  if ! grep -qE -- "$pattern" "$TMP/err"; then fail "$what: stderr does not match '$pattern': $(cat "$TMP/err")"; return; fi
  if [ "$(grep -c . "$TMP/err")" -ne 1 ]; then fail "$what: $(grep -c . "$TMP/err") lines on stderr: $(cat "$TMP/err")"; return; fi
  ok
}
