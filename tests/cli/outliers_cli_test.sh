#!/usr/bin/env bash
# `pathlab outliers` end to end (issue 34): the list is sorted brightest first; each outlier's record
# is the technique named, its weighted luminance is the outlier's, its densities recompute its weight
# and its density ratio (its own p over the largest counted p, python3); in the caustic scene the
# brightest is a camera path through the glass that light tracing samples far more likely; bad input
# is one line and a non-zero exit; the JSON is not overwritten without --force.
source "$(dirname "$0")/cli_lib.sh"

CAUSTIC="$SRC/assets/caustic.gltf"

check_outliers() {
  python3 - "$1" <<'PY'
import json, math, sys
j = json.load(open(sys.argv[1]))
out = j["outliers"]
assert len(out) == 6, len(out)
lums = [o["luminance"] for o in out]
assert lums == sorted(lums, reverse=True), lums
n_ratio = j["lightTracingSampleRatio"]
for o in out:
    r = o["record"]
    assert (r["s"], r["t"], r["kind"]) == (o["technique"]["s"], o["technique"]["t"], o["technique"]["kind"]), (r, o)
    w = [c * r["weight"] for c in r["contribution"]]
    lum = 0.2126 * w[0] + 0.7152 * w[1] + 0.0722 * w[2]
    assert math.isclose(lum, o["luminance"], rel_tol=1e-4), (lum, o["luminance"])
    d = r["densities"]
    own = d[r["s"]]
    counted = [x for x in d if x["counted"]]
    n = lambda x: n_ratio if x["t"] == 1 else 1.0
    weight = 1.0 / sum((n(x) * x["pdfA"] / (n(own) * own["pdfA"])) ** (j["beta"] if j["heuristic"] == "power" else 1.0)
                       for x in counted)
    assert math.isclose(weight, r["weight"], rel_tol=1e-4), (weight, r["weight"])
    best = max(counted, key=lambda x: x["pdfA"])
    assert math.isclose(o["densityRatio"], own["pdfA"] / best["pdfA"], rel_tol=1e-9), o
    assert (best["s"], best["t"]) == (o["bestTechnique"]["s"], o["bestTechnique"]["t"]), o
# The caustic's fireflies: camera paths that hit the light through the glass (s = 0), which light
# tracing samples with a far larger density.
top = out[0]
assert top["technique"]["s"] == 0 and top["densityRatio"] < 0.2 and top["bestTechnique"]["t"] == 1, top
PY
}

if "$PATHLAB" outliers "$CAUSTIC" --width 128 --height 128 --spp 16 --top 6 --json "$TMP/o.json" >"$TMP/out" 2>"$TMP/err" \
     </dev/null && grep -q "the 6 brightest weighted contributions" "$TMP/out" && check_outliers "$TMP/o.json" 2>"$TMP/py"; then ok
else fail "outliers: $(cat "$TMP/err" "$TMP/py" 2>/dev/null | tail -5)"; fi
expect_error "existing JSON" "exists" outliers "$CAUSTIC" --width 32 --height 32 --spp 1 --json "$TMP/o.json"
expect_error "path tracer" "use --integrator bpt, lt, vcm, bpm or ppm" outliers "$CAUSTIC" --integrator pt
expect_error "mlt" "not mlt" outliers "$CAUSTIC" --integrator mlt
expect_error "absurd --top" "--top 5000 is outside" outliers "$CAUSTIC" --top 5000
expect_error "absurd --spp" "--spp 0 is outside" outliers "$CAUSTIC" --spp 0
expect_error "missing scene" "nope.gltf" outliers "$TMP/nope.gltf"

echo "outliers_cli: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
