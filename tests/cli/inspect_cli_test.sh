#!/usr/bin/env bash
# `pathlab inspect` end to end: the text names every technique; the JSON has the documented fields,
# its subpaths start on an emitter and at the camera, and every technique's weights are recomputed
# from its listed densities (python3, which dev.sh installs); the JSON is not overwritten without
# --force; a Metropolis chain's state is the chain's (its F is its technique's weighted contribution
# times the technique count); bad input is one line and a non-zero exit.
source "$(dirname "$0")/cli_lib.sh"

BOX="$SRC/assets/cornell-box.gltf"
VEACH="$SRC/assets/veach-mis.gltf"

check_json() {
  python3 - "$1" "$2" <<'PY'
import json, math, sys
j = json.load(open(sys.argv[1]))
heuristic = sys.argv[2]
for key in ["pixel", "sample", "seed", "heuristic", "cameraSubpath", "lightSubpath", "techniques"]:
    assert key in j, key
assert j["heuristic"] == heuristic, j["heuristic"]
assert j["cameraSubpath"][0]["kind"] == "camera"
assert j["lightSubpath"][0]["kind"] == "light"
n_ratio = j["lightTracingSampleRatio"]
checked = 0
for t in j["techniques"]:
    for key in ["s", "t", "enabled", "blocked", "contribution", "weight", "raster", "path", "densities"]:
        assert key in t, key
    if not t["path"]:
        continue
    assert len(t["path"]) == t["s"] + t["t"]
    assert t["vertices"][-1]["kind"] == "camera"
    d = t["densities"]
    own = d[t["s"]]
    counted = [x for x in d if x["counted"]]
    if not own["counted"]:
        continue
    n = lambda x: n_ratio if x["t"] == 1 else 1.0
    for name, b in [("balance", 1.0), ("power", j["beta"])]:
        w = 1.0 / sum((n(x) * x["pdfA"] / (n(own) * own["pdfA"])) ** b for x in counted)
        assert math.isclose(w, t["weights"][name], rel_tol=1e-6), (name, w, t["weights"][name])
    assert math.isclose(t["weights"]["uniform"], 1.0 / len(counted), rel_tol=1e-9)
    if not t["blocked"] and any(t["contribution"]):
        assert math.isclose(t["weight"], t["weights"][heuristic], rel_tol=1e-5, abs_tol=1e-7), (t["weight"], t["weights"])
    # The densities multiply out from the path's vertex densities (a zero counts one).
    for x in d:
        if not x["possible"]:
            continue
        p = 1.0
        for i, v in enumerate(t["vertices"]):
            # Technique (1, t >= 2) samples x0 by next-event estimation: its own density of x0.
            q = (v.get("pdfFromLightNeeA", v["pdfFromLightA"]) if i == 0 and x["s"] == 1
                 else v["pdfFromLightA"] if i < x["s"] else v["pdfFromCameraA"])
            p *= q if q != 0 else 1.0
        assert math.isclose(p, x["pdfA"], rel_tol=1e-9), (p, x["pdfA"])
    checked += 1
assert checked >= 2, checked
PY
}

for h in balance power; do
  if "$PATHLAB" inspect "$BOX" --pixel 200,300 --sample 3 --max-length 4 --mis "$h" --json "$TMP/$h.json" \
       >"$TMP/out" 2>"$TMP/err" </dev/null &&
     grep -q "this path under every technique" "$TMP/out" && check_json "$TMP/$h.json" "$h" 2>"$TMP/py"; then ok
  else fail "inspect --mis $h: $(cat "$TMP/err" "$TMP/py" 2>/dev/null | tail -5)"; fi
done
# Vertex merging (--integrator vcm): a merge names its two vertices within the radius, and the
# weights of every technique of a path's length, connections and merges, sum to one.
SPHERES="$SRC/assets/cornell-spheres.gltf"
check_merge_json() {
  python3 - "$1" <<'PY'
import json, math, sys
j = json.load(open(sys.argv[1]))
merges = 0
for t in j["techniques"]:
    if not t["densities"] or not t["weight"] > 0:
        continue
    # A length k has k + 1 connections and k - 1 merges.
    k = len(t["densities"]) // 2
    assert [x["kind"] for x in t["densities"]] == ["connection"] * (k + 1) + ["merge"] * (k - 1), t["densities"]
    assert math.isclose(sum(x["weights"][j["heuristic"]] for x in t["densities"]), 1.0, rel_tol=1e-4), t
    if t["kind"] != "merge":
        continue
    for key in ["lightVertex", "cameraVertex", "distance", "radius", "contribution", "weight", "weights"]:
        assert key in t, key
    assert 0 <= t["distance"] <= t["radius"] * (1 + 1e-5), (t["distance"], t["radius"])
    merges += 1
assert merges >= 1, merges
PY
}
if "$PATHLAB" inspect "$SPHERES" --integrator vcm --radius 0.05 --width 64 --height 64 --max-length 4 --pixel 32,40 \
     --json "$TMP/vcm.json" >"$TMP/out" 2>"$TMP/err" </dev/null &&
   grep -q "merges light vertex" "$TMP/out" && check_merge_json "$TMP/vcm.json" 2>"$TMP/py"; then ok
else fail "inspect --integrator vcm: $(cat "$TMP/err" "$TMP/py" 2>/dev/null | tail -5)"; fi
"$PATHLAB" render "$SPHERES" --integrator bpm --radius 0.05 --width 64 --height 64 --max-length 4 --replay 32,40,2 \
  >"$TMP/out" 2>"$TMP/err" && grep -q "^ *M(2,2)" "$TMP/out" && ok || fail "render --replay with merges: $(tail -3 "$TMP/err")"

# Metropolis (--integrator mlt): a chain's state, with the primary numbers its path read, its
# technique and its one record, whose MIS-weighted contribution times the length's technique count
# is the chain's F; the same chain after more passes is elsewhere (its state moved).
check_chain_json() {
  python3 - "$1" "$2" <<'PY'
import json, math, sys
j = json.load(open(sys.argv[1]))
c = j["chain"]
for key in ["index", "chains", "variant", "length", "technique", "f", "contributions", "primaryNumbers"]:
    assert key in c, key
assert c["index"] == 7 and c["variant"] == "mmlt" and j["sample"] == int(sys.argv[2]), c
s, t = c["technique"]
assert s + t - 1 == c["length"], c
numbers = c["primaryNumbers"]
assert numbers["camera"], numbers  # the technique's choice, the film position, the lens
assert all(0 <= u < 1 for stream in numbers.values() for u in stream), numbers
[record] = j["techniques"]
assert (record["s"], record["t"]) == (s, t), record
if c["f"] > 0:
    [x] = c["contributions"]
    n = c["length"] + 1  # every technique of the length is enabled
    for a, b, w in zip(x["value"], record["contribution"], [record["weight"]] * 3):
        assert math.isclose(a, n * w * b, rel_tol=1e-4), (x, record)
    luminance = 0.2126 * x["value"][0] + 0.7152 * x["value"][1] + 0.0722 * x["value"][2]
    assert math.isclose(luminance, c["f"], rel_tol=1e-4), (luminance, c["f"])
    assert len(record["path"]) == c["length"] + 1
print(json.dumps(numbers))
PY
}
for pass in 0 3; do
  if "$PATHLAB" inspect "$BOX" --integrator mlt --chain 7 --pass "$pass" --width 48 --height 48 --max-length 4 \
       --bootstrap 2000 --chains 50 --json "$TMP/chain$pass.json" --force >"$TMP/out" 2>"$TMP/err" </dev/null &&
     grep -q "primary numbers the path read" "$TMP/out" && grep -q "^chain 7 of" "$TMP/out" &&
     check_chain_json "$TMP/chain$pass.json" "$pass" >"$TMP/numbers$pass" 2>"$TMP/py"; then ok
  else fail "inspect --integrator mlt --pass $pass: $(cat "$TMP/err" "$TMP/py" 2>/dev/null | tail -5)"; fi
done
cmp -s "$TMP/numbers0" "$TMP/numbers3" && fail "the chain's numbers did not move in 3 passes" || ok
expect_error "mlt with --pixel" "give --chain C" inspect "$BOX" --integrator mlt --pixel 1,1
expect_error "mlt without --chain" "give the chain to inspect" inspect "$BOX" --integrator mlt
expect_error "--chain without mlt" "use them with --integrator mlt" inspect "$BOX" --chain 1
expect_error "chain past the last" "past the last chain" inspect "$BOX" --integrator mlt --chain 5000 --width 32 \
  --height 32 --bootstrap 100
expect_error "absurd --pass" "more than 4096 passes" inspect "$BOX" --integrator mlt --chain 1 --pass 99999
expect_error "no pixel" "give the pixel to inspect" inspect "$BOX"

# Variance-aware MIS: sample 12 is replayed with the factors of passes 0..11 (rendered first), so
# each record's weight is its variance-aware weight, the path's variance-aware weights over the
# counted techniques sum to one, and the factors (not all 1 after the pilot passes) are shown.
if "$PATHLAB" inspect "$BOX" --mis variance-aware --pixel 30,40 --sample 12 --width 64 --height 64 --max-length 4 \
     --json "$TMP/va.json" --force >"$TMP/out" 2>"$TMP/err" </dev/null && grep -q "var-aware" "$TMP/out" &&
   python3 - "$TMP/va.json" >"$TMP/py" 2>&1 <<'PY'
import json, math, sys
j = json.load(open(sys.argv[1]))
factors, weighed = [], 0
for r in j["techniques"]:
    if not r.get("densities") or "weights" not in r:
        continue
    assert math.isclose(r["weight"], r["weights"]["variance-aware"], rel_tol=1e-5, abs_tol=1e-7), r["weights"]
    total = sum(x["weights"]["variance-aware"] for x in r["densities"] if x["counted"])
    assert math.isclose(total, 1.0, rel_tol=1e-5), total
    factors += [x["factor"] for x in r["densities"] if x["possible"]]
    weighed += 1
assert weighed >= 3, weighed
assert any(abs(f - 1) > 0.05 for f in factors), factors
PY
then ok; else fail "inspect --mis variance-aware: $(cat "$TMP/err" "$TMP/py" 2>/dev/null | tail -5)"; fi
# Optimal MIS: sample 20 is replayed after passes 0..19 (coefficients solved after 4, 8 and 16), so each
# contributed connection shows its correction, which is beta_s - sum_k beta_k w_k over the balance weights
# of its path, and the coefficients are not all zero.
if "$PATHLAB" inspect "$BOX" --mis optimal --pixel 30,40 --sample 20 --width 64 --height 64 --max-length 4 \
     --json "$TMP/optimal.json" --force >"$TMP/out" 2>"$TMP/err" </dev/null && grep -q "optimal MIS correction" "$TMP/out" &&
   python3 - "$TMP/optimal.json" >"$TMP/py" 2>&1 <<'PY'
import json, math, sys
j = json.load(open(sys.argv[1]))
checked, nonzero = 0, 0
for r in j["techniques"]:
    if "optimal" not in r:
        continue
    beta = r["optimal"]["beta"]
    w = [0.0] * len(beta)
    for x in r["densities"]:
        if x["kind"] == "connection" and x["counted"]:
            w[x["s"]] = x["weights"]["balance"]
    for c in range(3):
        expected = beta[r["s"]][c] - sum(b[c] * wk for b, wk in zip(beta, w))
        assert math.isclose(r["optimal"]["correction"][c], expected, rel_tol=1e-4, abs_tol=1e-6), (r, expected)
    nonzero += any(abs(b[c]) > 0 for b in beta for c in range(3))
    checked += 1
assert checked >= 3 and nonzero >= 1, (checked, nonzero)
PY
then ok; else fail "inspect --mis optimal: $(cat "$TMP/err" "$TMP/py" 2>/dev/null | tail -5)"; fi
expect_error "variance-aware sample too far" "at most 4096" inspect "$BOX" --mis variance-aware --pixel 1,1 --sample 5000
expect_error "variance-aware with mlt" "--mis variance-aware needs the bpt or lt integrator" render "$BOX" \
  --integrator mlt --mis variance-aware -o "$TMP/x.exr"
expect_error "variance-aware with pt" "weighs the bidirectional techniques" render "$BOX" --integrator pt \
  --mis variance-aware -o "$TMP/x.exr"

# Not overwritten without --force; with it, it is.
expect_error "existing JSON" "exists" inspect "$BOX" --pixel 1,1 --json "$TMP/balance.json"
"$PATHLAB" inspect "$VEACH" --pixel 100,100 --json "$TMP/balance.json" --force >/dev/null 2>&1 && ok || fail "--force"
expect_error "pixel outside" "outside the 512 x 341 image" inspect "$VEACH" --pixel 600,10
expect_error "pixel syntax" "is not X,Y" inspect "$BOX" --pixel 10
expect_error "sample past the limit" "past the last sample" inspect "$BOX" --pixel 1,1 --sample 99999999
expect_error "missing scene" "nope.gltf" inspect "$TMP/nope.gltf" --pixel 1,1
expect_error "path tracer" "bpt, lt or mlt" inspect "$BOX" --pixel 1,1 --integrator pt

# --light-paths auto: a word or a number, the balance heuristic, one process; inspect replays the
# passes before the sample (their choices) as for variance-aware MIS.
expect_error "light-paths word" "--light-paths.*'banana' is neither auto nor a number" render "$BOX" --light-paths banana -o "$TMP/x.exr"
expect_error "light-paths nan" "--light-paths.*'nan' is neither auto nor a number" render "$BOX" --light-paths nan -o "$TMP/x.exr"
expect_error "light-paths auto, power" "--light-paths auto estimates the balance heuristic's" render "$BOX" --light-paths auto \
  --mis power -o "$TMP/x.exr"
expect_error "light-paths auto, pt" "use bpt, not pt" render "$BOX" --light-paths auto --integrator pt -o "$TMP/x.exr"
expect_error "light-paths auto, sample too far" "--sample 5000 under --light-paths auto.*at most 4096" inspect "$BOX" \
  --light-paths auto --pixel 1,1 --sample 5000
expect_error "converge light-paths=auto, power" "--light-paths auto estimates" converge "$BOX" -o "$TMP/conv-lp" \
  --configs "bpt:light-paths=auto,mis=power"
expect_error "light-paths auto, replay" "--replay sample 9 under --light-paths auto.*pathlab inspect" render "$BOX" \
  --light-paths auto --replay 3,4,9
if "$PATHLAB" render "$BOX" --light-paths auto --width 32 --height 32 --spp 8 -o "$TMP/auto.exr" --force 2>"$TMP/err" &&
   grep -q "light paths auto: F = .* (chosen 2 times from 4 learning passes)" "$TMP/err"
then ok; else fail "render --light-paths auto: $(tail -3 "$TMP/err")"; fi

# --mis optimal: bpt's connections, one process; its image differs from balance's past the pilot passes.
expect_error "optimal with lt" "--mis optimal corrects the connections' balance weights: use bpt, not lt" render "$BOX" \
  --integrator lt --mis optimal -o "$TMP/x.exr"
expect_error "optimal with merges" "--mis optimal weighs connections only" render "$BOX" --techniques "all;m=all" \
  --mis optimal -o "$TMP/x.exr"
expect_error "optimal, naive" "--mis optimal needs path reuse" render "$BOX" --connect endpoints --mis optimal -o "$TMP/x.exr"
expect_error "optimal, equiangular" "use --medium-sampling distance, not mis" render "$BOX" --medium-sampling mis \
  --mis optimal -o "$TMP/x.exr"
expect_error "optimal, isolate" "--isolate shows one technique unweighted: it takes no --mis optimal" render "$BOX" \
  --isolate 1,2 --mis optimal -o "$TMP/x.exr"
expect_error "optimal, replay" "--replay sample 9 under --mis optimal.*pathlab inspect" render "$BOX" --mis optimal \
  --replay 3,4,9
expect_error "optimal, fog" "--mis optimal is not available in a scene with media" render "$SRC/assets/fog.gltf" \
  --mis optimal -o "$TMP/x.exr"
expect_error "converge optimal, vcm" "--mis optimal weighs connections only" converge "$BOX" -o "$TMP/conv-opt" --configs "vcm:mis=optimal"
if "$PATHLAB" render "$BOX" --mis optimal --width 32 --height 32 --spp 9 --seed 3 -o "$TMP/optimal.pfm" --force 2>"$TMP/err" &&
   "$PATHLAB" render "$BOX" --width 32 --height 32 --spp 9 --seed 3 -o "$TMP/balance.pfm" --force 2>>"$TMP/err" &&
   ! cmp -s "$TMP/optimal.pfm" "$TMP/balance.pfm"
then ok; else fail "render --mis optimal: $(tail -3 "$TMP/err")"; fi

echo "inspect_cli: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
