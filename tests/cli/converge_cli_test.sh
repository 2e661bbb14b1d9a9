#!/usr/bin/env bash
# End-to-end checks of `pathlab converge`: a tiny run writes a well-formed CSV whose error falls
# with time, a valid SVG with one polyline per configuration and the efficiency table; the
# reference is cached by hash and reused; bad input gives one line and a non-zero exit.
source "$(dirname "$0")/cli_lib.sh"

BOX="$SRC/assets/cornell-box.gltf"
OUT="$TMP/conv"
RUN=(converge "$BOX" -o "$OUT" --configs "bpt;pt" --time 0.5 --reference-time 1 --width 16 --height 16 --max-length 4)

if "$PATHLAB" "${RUN[@]}" >"$TMP/table" 2>"$TMP/log" </dev/null; then ok; else fail "converge run: $(cat "$TMP/log")"; fi

# The CSV: a header, rows of both configurations, relMSE falling by at least half from the first
# checkpoint (1 spp) to the last (thousands of spp; the reference has twice the time).
python3 - "$OUT/convergence.csv" <<'PY' && ok || fail "convergence.csv"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert rows, "no rows"
for key in ("config", "spp", "seconds", "rmse", "relmse", "mape", "twobuffer_mse", "twobuffer_relmse"):
    assert key in rows[0], f"missing column {key}"
configs = sorted({r["config"] for r in rows})
assert configs == ["bpt", "pt"], configs
for c in configs:
    mine = [r for r in rows if r["config"] == c]
    assert len(mine) >= 3, f"{c}: {len(mine)} checkpoints"
    times = [float(r["seconds"]) for r in mine]
    assert times == sorted(times), f"{c}: times not increasing"
    assert times[-1] >= 0.5, f"{c}: rendered only {times[-1]} s"
    first, last = float(mine[0]["relmse"]), float(mine[-1]["relmse"])
    assert last < 0.5 * first, f"{c}: relMSE {first} -> {last}"
    assert float(mine[-1]["twobuffer_relmse"]) > 0, f"{c}: no two-buffer estimate"
PY

python3 - "$OUT/convergence.svg" <<'PY' && ok || fail "convergence.svg"
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
assert root.tag == "{http://www.w3.org/2000/svg}svg", root.tag
lines = root.findall(".//{http://www.w3.org/2000/svg}polyline")
assert len(lines) == 2, f"{len(lines)} polylines"
for l in lines:
    assert len(l.get("points").split()) >= 3, "a line with fewer than 3 points"
PY

[ "$(grep -c '^| `' "$OUT/efficiency.md")" -eq 2 ] && ok || fail "efficiency.md: $(cat "$OUT/efficiency.md")"
grep -q 'speed-up' "$TMP/table" && ok || fail "the table is not printed"
ls "$OUT"/reference-*.exr >/dev/null 2>&1 && ok || fail "no cached reference"

# No overwrite without --force; with it, the cached reference is reused.
expect_error "existing results" "convergence.csv.*--force" "${RUN[@]}"
if "$PATHLAB" "${RUN[@]}" --force >/dev/null 2>"$TMP/log" </dev/null && grep -q "reusing" "$TMP/log"; then ok
else fail "second run does not reuse the reference: $(cat "$TMP/log")"; fi

# An explicit reference fixes the size.
REF=$(ls "$OUT"/reference-*.exr | head -1)
if "$PATHLAB" converge "$BOX" -o "$TMP/explicit" --reference "$REF" --configs lt --time 0.2 --max-length 4 \
    --clock cpu --threads 1 >/dev/null 2>"$TMP/log" </dev/null && grep -q "CPU time" "$TMP/explicit/efficiency.md"
then ok; else fail "explicit reference, CPU clock: $(cat "$TMP/log")"; fi

# --mask: the errors over the masked pixels only (here where the reference is bright), said in the
# table; a mask of another size, or one selecting nothing, is one line before any work.
python3 - "$TMP" <<'PY'
import struct, sys
def pfm(path, w, h, v):
    open(path, "wb").write(b"PF\n%d %d\n-1.0\n" % (w, h) + struct.pack("<%df" % (3 * w * h), *([v] * (3 * w * h))))
pfm(sys.argv[1] + "/mask-8.pfm", 8, 8, 1.0)
pfm(sys.argv[1] + "/mask-black.pfm", 16, 16, 0.0)
PY
if "$PATHLAB" converge "$BOX" -o "$TMP/masked" --reference "$REF" --mask "$REF" --configs bpt --time 0.2 --max-length 4 \
    >/dev/null 2>"$TMP/log" </dev/null && grep -q "inside the mask .* of the 256 pixels" "$TMP/masked/efficiency.md"
then ok; else fail "masked run: $(cat "$TMP/log") $(cat "$TMP/masked/efficiency.md" 2>/dev/null)"; fi
expect_error "mask of another size" "mask-8.pfm: the mask is 8 x 8, the images 16 x 16" converge "$BOX" -o "$TMP/m2" \
  --reference "$REF" --mask "$TMP/mask-8.pfm" --configs bpt --time 0.1
expect_error "mask selecting nothing" "mask-black.pfm: the mask selects no pixel" converge "$BOX" -o "$TMP/m3" \
  --reference "$REF" --mask "$TMP/mask-black.pfm" --configs bpt --time 0.1
expect_error "missing mask" "nothing.exr" converge "$BOX" -o "$TMP/m4" --reference "$REF" --mask "$TMP/nothing.exr" \
  --configs bpt --time 0.1

# Bad input: one line, before any work.
C=(converge "$BOX" -o "$TMP/bad" --time 0.1 --width 8 --height 8)
expect_error "unknown integrator" "magic" "${C[@]}" --configs "bpt;magic"
expect_error "mis for pt" "pt:mis=power.*bpt and lt" "${C[@]}" --configs "pt:mis=power"
expect_error "connect for pt" "pt:connect=endpoints.*bpt and lt" "${C[@]}" --configs "pt:connect=endpoints"
expect_error "unknown connect" "connect strategy 'some'" "${C[@]}" --configs "bpt:connect=some"
expect_error "unknown key" "foo" "${C[@]}" --configs "bpt:foo=1"
expect_error "too long technique" "9,9" "${C[@]}" --configs "bpt:techniques=9,9,max-length=4"
expect_error "duplicate config" "twice" "${C[@]}" --configs "pt;pt"
expect_error "empty configs" "no configuration" "${C[@]}" --configs ";"
expect_error "spp with time" "time|spp" "${C[@]}" --spp 4
expect_error "unknown clock" "clock" "${C[@]}" --clock sundial
expect_error "missing reference" "nope\.exr" "${C[@]}" --reference "$TMP/nope.exr"
expect_error "reference size" "16 x 16" "${C[@]}" --reference "$REF"
expect_error "reference and its budget" "reference" "${C[@]}" --reference "$REF" --reference-time 3
expect_error "missing scene" "nope\.gltf" converge "$TMP/nope.gltf" -o "$TMP/bad" --time 0.1
touch "$TMP/afile"
expect_error "output is a file" "afile.*not a directory" converge "$BOX" -o "$TMP/afile" --time 0.1
[ ! -e "$TMP/bad" ] && ok || fail "a refused run created its output directory"

echo "converge CLI: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
