#!/usr/bin/env bash
# `pathlab check` end to end (issue 13, part 4): exit 0 when the techniques agree, 1 naming the
# one made wrong by --inject-bias, and one line and a non-zero exit for options it cannot use.
source "$(dirname "$0")/cli_lib.sh"

BOX="$SRC/assets/cornell-box.gltf"
QUICK=(--spp 300 --width 32 --height 32 --max-length 2 --threads 2)

"$PATHLAB" check "$BOX" "${QUICK[@]}" >"$TMP/out" 2>"$TMP/err"
code=$?
[ "$code" -eq 0 ] && ok || fail "check of the Cornell box: exit $code: $(cat "$TMP/out" "$TMP/err")"
grep -q "verdict: every compared technique agrees" "$TMP/out" && ok || fail "no agreeing verdict: $(cat "$TMP/out")"
[ "$(grep -cE '^\([0-9]+,[0-9]+\) ' "$TMP/out")" -eq 5 ] && ok || fail "not one line per technique of lengths 1-2: $(cat "$TMP/out")"

# A 50 % bias on (1,2): named, alone, exit 1, and said on stderr.
"$PATHLAB" check "$BOX" "${QUICK[@]}" --inject-bias 1,2,1.5 >"$TMP/out" 2>"$TMP/err"
code=$?
[ "$code" -eq 1 ] && ok || fail "an injected bias: exit $code: $(cat "$TMP/out")"
grep -qE '^\(1,2\) .*DISAGREES' "$TMP/out" && ok || fail "(1,2) not named: $(cat "$TMP/out")"
[ "$(grep -c DISAGREES "$TMP/out")" -eq 1 ] && ok || fail "more than the biased technique named: $(cat "$TMP/out")"
grep -q "deliberately wrong" "$TMP/err" && ok || fail "no warning of the injected bias: $(cat "$TMP/err")"

# vcm: the merge judged by its difference from the connections against the radius (r, r/2, r/4),
# in the text and the JSON; with its normalisation doubled, named, and exit 1.
VCM=(--integrator vcm --radius 0.08 --spp 150 --width 32 --height 32 --max-length 2 --threads 2)
"$PATHLAB" check "$BOX" "${VCM[@]}" --json "$TMP/check.json" >"$TMP/out" 2>"$TMP/err"
code=$?
[ "$code" -eq 0 ] && ok || fail "vcm check of the Cornell box: exit $code: $(cat "$TMP/out" "$TMP/err")"
grep -qE '^M\(2,2\) .*agrees' "$TMP/out" && grep -q 'r = 0.02' "$TMP/out" && ok || fail "no merge line: $(cat "$TMP/out")"
python3 - "$TMP/check.json" <<'PY' && ok || fail "check.json: $(cat "$TMP/check.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["agrees"] is True
assert [round(r, 4) for r in j["merges"]["radii"]] == [0.08, 0.04, 0.02], j["merges"]["radii"]
m = j["merges"]["techniques"]
assert [t["technique"] for t in m] == ["M(2,2)"], m
assert len(m[0]["wholeImage"]) == 3 and "extrapolated" in m[0], m[0]
assert len(j["techniques"]) == 5, j["techniques"]
PY
"$PATHLAB" check "$BOX" "${VCM[@]}" --inject-bias M2,2,2 >"$TMP/out" 2>"$TMP/err"
code=$?
[ "$code" -eq 1 ] && ok || fail "a merge's normalisation doubled: exit $code: $(cat "$TMP/out")"
grep -qE '^M\(2,2\) .*DISAGREES' "$TMP/out" && ok || fail "M(2,2) not named: $(cat "$TMP/out")"
grep -q "technique M(2,2) is multiplied by 2" "$TMP/err" && ok || fail "no warning of the injected bias: $(cat "$TMP/err")"
expect_error "check vcm --radius-alpha 0.75" "radius-alpha 0.75" check "$BOX" --integrator vcm --radius-alpha 0.75
expect_error "--inject-bias M1,2" "a merge needs s >= 2" render "$BOX" -o "$TMP/x.png" --inject-bias M1,2,2

expect_error "check --integrator pt" "bpt or lt" check "$BOX" --integrator pt
expect_error "check --isolate" "not with --isolate" check "$BOX" --isolate 1,2
expect_error "check --max-length 40" "at most 30 edges" check "$BOX" --max-length 40
expect_error "check --spp 1" "--spp" check "$BOX" --spp 1
expect_error "check --blocks 0" "--blocks" check "$BOX" --blocks 0
expect_error "check --alpha nan" "--alpha.*nan" check "$BOX" --alpha nan
expect_error "--inject-bias 1,2" "not S,T,FACTOR" check "$BOX" --inject-bias 1,2
expect_error "--inject-bias factor nan" "outside 0" render "$BOX" -o "$TMP/x.png" --inject-bias 1,2,nan
expect_error "--inject-bias factor -1" "outside 0" render "$BOX" -o "$TMP/x.png" --inject-bias 1,2,-1
expect_error "--inject-bias x" "not a number" render "$BOX" -o "$TMP/x.png" --inject-bias 1,2,x
expect_error "--inject-bias (0,1)" "does not exist" render "$BOX" -o "$TMP/x.png" --inject-bias 0,1,1.1
expect_error "--inject-bias too long" "more than the maximum length" render "$BOX" -o "$TMP/x.png" --max-length 2 --inject-bias 2,2,1.1
expect_error "--inject-bias with pt" "bpt or lt" render "$BOX" -o "$TMP/x.png" --integrator pt --inject-bias 1,2,1.1
expect_error "view --z-map without --check" "needs --check" view "$BOX" --z-map 1,2
expect_error "view --z-map 9,9" "--z-map" view "$BOX" --check --z-map 9,9

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
