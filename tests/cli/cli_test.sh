#!/usr/bin/env bash
# End-to-end checks of `pathlab render` as a user meets it: renders of every bundled scene that
# contain no NaN, and bad input that gives one line naming the problem and a non-zero exit.
source "$(dirname "$0")/cli_lib.sh"

# Bad scenes: the message names the file (no-emitter.gltf is bad only without the default light).
for f in "$SRC"/tests/scenes/bad/*.gltf "$SRC"/tests/scenes/bad/*.glb; do
  [ -e "$f" ] || continue
  case "$(basename "$f")" in degenerate.gltf) continue ;; esac
  expect_error "bad scene $(basename "$f")" "$(basename "$f")" render "$f" -o "$TMP/x.pfm" --spp 1 --width 8 --height 8 \
    --no-default-light
done
expect_error "missing scene" "nope\.gltf" render "$TMP/nope.gltf" -o "$TMP/x.pfm"

# Absurd options are refused before any work.
BOX="$SRC/assets/cornell-box.gltf"
expect_error "zero spp" "spp" render "$BOX" -o "$TMP/x.pfm" --spp 0
expect_error "huge spp" "spp" render "$BOX" -o "$TMP/x.pfm" --spp 1000000000000
expect_error "negative width" "width" render "$BOX" -o "$TMP/x.pfm" --width -5
expect_error "huge image" "width|pixels" render "$BOX" -o "$TMP/x.pfm" --width 100000 --height 100000
expect_error "too many pixels" "pixels" render "$BOX" -o "$TMP/x.pfm" --width 16384 --height 16384
expect_error "unknown option" "--bogus" render "$BOX" -o "$TMP/x.pfm" --bogus
expect_error "unknown integrator" "integrator" render "$BOX" -o "$TMP/x.pfm" --integrator magic
expect_error "unknown heuristic" "mis" render "$BOX" -o "$TMP/x.pfm" --mis maximum
expect_error "unknown connect" "connect" render "$BOX" -o "$TMP/x.pfm" --connect some
expect_error "bad technique" "techniques" render "$BOX" -o "$TMP/x.pfm" --techniques "1;x"
expect_error "too long technique" "9,9" render "$BOX" -o "$TMP/x.pfm" --techniques "9,9" --max-length 4
expect_error "unknown extension" "\.bmp" render "$BOX" -o "$TMP/x.bmp" --spp 1
expect_error "spp with time" "time|spp" render "$BOX" -o "$TMP/x.pfm" --spp 4 --time 1
expect_error "zero max length" "max-length" render "$BOX" -o "$TMP/x.pfm" --max-length 0
expect_error "isolate not S,T" "isolate" render "$BOX" -o "$TMP/x.pfm" --isolate 3
expect_error "isolate too long" "length 6" render "$BOX" -o "$TMP/x.pfm" --isolate 3,4 --max-length 4
expect_error "isolate with pt" "bpt or lt" render "$BOX" -o "$TMP/x.pfm" --isolate 1,2 --integrator pt
expect_error "unweighted alone" "unweighted" render "$BOX" -o "$TMP/x.pfm" --unweighted
expect_error "pyramid with pt" "pyramid" render "$BOX" -o "$TMP/x.pfm" --pyramid 2 --integrator pt
expect_error "pyramid too long" "pyramid" render "$BOX" -o "$TMP/x.pfm" --pyramid 9
expect_error "missing directory" "no-such-dir" render "$BOX" -o "$TMP/no-such-dir/x.pfm" --spp 1 --width 8 --height 8

# Nothing the user made is overwritten without asking.
echo "precious" >"$TMP/keep.png"
expect_error "existing output" "exists" render "$BOX" -o "$TMP/keep.png" --spp 1 --width 8 --height 8
if [ "$(cat "$TMP/keep.png")" = "precious" ]; then ok; else fail "existing output was overwritten"; fi

# The technique pyramid writes one image per technique and two mosaics, and refuses to
# overwrite any of them.
if "$PATHLAB" render "$BOX" -o "$TMP/pyr.pfm" --spp 1 --width 16 --height 12 --pyramid 2 2>"$TMP/err"; then
  count=$(ls "$TMP"/pyr-s*-t*.pfm | wc -l)
  [ "$count" -eq 10 ] && [ -s "$TMP/pyr-pyramid.png" ] && [ -s "$TMP/pyr-pyramid-unweighted.png" ] && ok ||
    fail "pyramid files: $count technique images"
else fail "pyramid render: $(cat "$TMP/err")"; fi
rm -f "$TMP/pyr.pfm"
expect_error "pyramid file exists" "pyr-s0-t2.pfm: file exists" render "$BOX" -o "$TMP/pyr.pfm" --spp 1 --width 16 --height 12 --pyramid 2
"$PATHLAB" render "$BOX" -o "$TMP/iso.pfm" --spp 1 --width 16 --height 12 --isolate 1,2 --unweighted 2>/dev/null && ok ||
  fail "isolated unweighted render"

# Naive BPT: --stats files each technique's own subpath rays under its row (no walk rows).
if "$PATHLAB" render "$BOX" -o "$TMP/naive.pfm" --spp 1 --width 16 --height 12 --max-length 3 --connect endpoints \
  --stats 2>"$TMP/err" && grep -qE '^\(2,2\) +[0-9]' "$TMP/err" && ! grep -q "camera walks" "$TMP/err"; then ok
else fail "naive stats: $(cat "$TMP/err")"; fi
# MIS off: one warning line naming the biased lengths and why (bidir-lamp: a spot light, glass);
# none in the Cornell box (area light, no delta BSDF).
LAMP="$SRC/assets/bidir-lamp.gltf"
if "$PATHLAB" render "$LAMP" -o "$TMP/off.pfm" --spp 1 --width 16 --height 12 --max-length 4 --mis off 2>"$TMP/err" &&
  [ "$(grep -c "mis off: lengths 1-4 biased" "$TMP/err")" -eq 1 ] && grep -q "spot light" "$TMP/err"; then ok
else fail "mis off warning: $(cat "$TMP/err")"; fi
if "$PATHLAB" render "$BOX" -o "$TMP/off2.pfm" --spp 1 --width 16 --height 12 --mis off 2>"$TMP/err" &&
  ! grep -q "mis off" "$TMP/err"; then ok
else fail "mis off warned on the Cornell box: $(cat "$TMP/err")"; fi
# --medium-sampling where no medium scatters changes nothing: one warning line; none in fog.
if "$PATHLAB" render "$BOX" -o "$TMP/ms.pfm" --spp 1 --width 16 --height 12 --integrator pt --medium-sampling distance \
  2>"$TMP/err" && [ "$(grep -c "medium-sampling distance changes nothing here" "$TMP/err")" -eq 1 ]; then ok
else fail "medium sampling warning: $(cat "$TMP/err")"; fi
if "$PATHLAB" render "$SRC/assets/fog-lamp.gltf" -o "$TMP/ms2.pfm" --spp 1 --width 16 --height 12 --integrator pt \
  --medium-sampling equiangular 2>"$TMP/err" && ! grep -q "changes nothing" "$TMP/err"; then ok
else fail "medium sampling warned in fog: $(cat "$TMP/err")"; fi
# bpt samples with its equiangular technique family on request (issue 35).
if "$PATHLAB" render "$SRC/assets/fog-lamp.gltf" -o "$TMP/ms4.pfm" --spp 1 --width 16 --height 12 --integrator bpt \
  --medium-sampling mis 2>"$TMP/err" && ! grep -q "changes nothing" "$TMP/err"; then ok
else fail "bpt --medium-sampling mis in fog: $(cat "$TMP/err")"; fi
# ...and where only density grids scatter (equiangular sampling declines them): the other warning.
if "$PATHLAB" render "$SRC/assets/smoke.gltf" -o "$TMP/ms3.pfm" --spp 1 --width 16 --height 12 --integrator pt \
  --medium-sampling mis 2>"$TMP/err" && [ "$(grep -c "every scattering medium is a density grid" "$TMP/err")" -eq 1 ]; then ok
else fail "medium sampling warning in smoke: $(cat "$TMP/err")"; fi
# make-volume: writes a grid the loader reads, refuses to overwrite without --force, and refuses
# an unknown kind and an absurd resolution in one line each.
if "$PATHLAB" make-volume ramp "$TMP/ramp.vdb" --resolution 8 >/dev/null && [ -s "$TMP/ramp.vdb" ] &&
  ! "$PATHLAB" make-volume ramp "$TMP/ramp.vdb" --resolution 8 2>"$TMP/err" && grep -q "file exists" "$TMP/err" &&
  "$PATHLAB" make-volume constant "$TMP/ramp.vdb" --resolution 8 --force >/dev/null; then ok
else fail "make-volume: $(cat "$TMP/err")"; fi
if ! "$PATHLAB" make-volume cloud "$TMP/c.vdb" 2>"$TMP/err" && [ "$(wc -l < "$TMP/err")" -eq 1 ] &&
  ! "$PATHLAB" make-volume smoke "$TMP/c.vdb" --resolution 100000 2>"$TMP/err2" && [ "$(wc -l < "$TMP/err2")" -eq 1 ] &&
  [ ! -e "$TMP/c.vdb" ]; then ok
else fail "make-volume refusals: $(cat "$TMP/err" "$TMP/err2")"; fi

# --replay prints one sample technique by technique; bad requests are one-line errors.
if "$PATHLAB" render "$BOX" --replay 5,6,2 --width 16 --height 12 --max-length 3 >"$TMP/replay" 2>"$TMP/err" &&
  grep -q "pixel 5,6 sample 2" "$TMP/replay" && grep -q "(1,2)" "$TMP/replay"; then ok; else fail "replay: $(cat "$TMP/replay" "$TMP/err")"; fi
expect_error "replay outside" "outside" render "$BOX" --replay 99,1,0 --width 16 --height 12
expect_error "replay not X,Y,S" "replay" render "$BOX" --replay 1,2 --width 16 --height 12
expect_error "no output" "output" render "$BOX" --spp 1

# Every bundled scene renders, in every format, without NaN or Inf pixels.
for scene in "$SRC"/assets/*.gltf "$SRC"/tests/scenes/cornell-box.glb; do
  name=$(basename "$scene")
  if ! "$PATHLAB" render "$scene" -o "$TMP/$name.pfm" --spp 2 --width 48 --height 36 --seed 1 2>"$TMP/err"; then
    fail "render $name: $(cat "$TMP/err")"; continue
  fi
  if ! grep -q "0 discarded" "$TMP/err"; then fail "render $name discarded samples: $(tail -1 "$TMP/err")"; continue; fi
  if python3 - "$TMP/$name.pfm" <<'PY'
import struct, sys, math
data = open(sys.argv[1], 'rb').read()
header = data.split(b'\n', 3)
w, h = map(int, header[1].split())
px = struct.unpack('<%df' % (3 * w * h), header[3][:12 * w * h])
bad = sum(1 for v in px if not math.isfinite(v) or v < 0)
lit = sum(1 for v in px if v > 0)
sys.exit(0 if bad == 0 and lit > 0 else 1)
PY
  then ok; else fail "render $name has NaN, Inf, negative or no light"; fi
done
# An orthographic camera (assets/isometric.gltf): nothing can connect to it (t = 1), and it has no lens.
ISO="$SRC/assets/isometric.gltf"
expect_error "light tracing through an orthographic camera" "orthographic camera.*use bpt or pt" \
  render "$ISO" -o "$TMP/iso-lt.pfm" --integrator lt --spp 1 --width 8 --height 6
expect_error "an aperture on an orthographic camera" "orthographic camera has no lens" \
  render "$ISO" -o "$TMP/iso-lens.pfm" --aperture 0.1 --spp 1 --width 8 --height 6
"$PATHLAB" render "$BOX" -o "$TMP/box.exr" --spp 1 --width 16 --height 16 2>/dev/null && [ -s "$TMP/box.exr" ] && ok || fail "exr output"
"$PATHLAB" render "$BOX" -o "$TMP/box.png" --time 0.2 --width 16 --height 16 2>/dev/null && [ -s "$TMP/box.png" ] && ok || fail "png output with --time"
"$PATHLAB" render --help | grep -q -- "--max-length" && ok || fail "render --help lacks --max-length"

# Lighting: a file without lights renders under the default light with one notice; an environment
# from a map or a colour; bad environments are one line naming the input.
NOLIGHT="$SRC/tests/scenes/bad/no-emitter.gltf"
if "$PATHLAB" render "$NOLIGHT" -o "$TMP/default.pfm" --spp 2 --width 8 --height 8 2>"$TMP/err" >/dev/null \
  && [ "$(grep -c "uniform white environment" "$TMP/err")" -eq 1 ]; then ok; else fail "default light: $(cat "$TMP/err")"; fi
for env in "$SRC/assets/sky.hdr" "0.2,0.3,0.4"; do
  "$PATHLAB" render "$SRC/assets/environment.gltf" -o "$TMP/env.pfm" --spp 1 --width 8 --height 8 --force \
    --environment "$env" --environment-strength 2 --environment-rotation 30 2>/dev/null && ok || fail "--environment $env"
done
"$PATHLAB" render "$BOX" -o "$TMP/box-env.pfm" --spp 1 --width 8 --height 8 --integrator pt --environment 1,1,1 \
  2>/dev/null && ok || fail "--environment with the scene's own lights"
printf 'not an image' > "$TMP/broken.exr"
expect_error "environment missing" "missing\.hdr: no such file" render "$BOX" -o "$TMP/x.pfm" --environment "$TMP/missing.hdr"
expect_error "environment broken" "broken\.exr: cannot read EXR" render "$BOX" -o "$TMP/x.pfm" --environment "$TMP/broken.exr"
expect_error "environment not a map" "x\.png: an environment is" render "$BOX" -o "$TMP/x.pfm" --environment "$TMP/x.png"
expect_error "environment colour" "1,-1,1: an environment colour" render "$BOX" -o "$TMP/x.pfm" --environment 1,-1,1
expect_error "environment strength alone" "environment-strength.*requires.*environment|environment-strength.*--environment" \
  render "$BOX" -o "$TMP/x.pfm" --environment-strength 2
expect_error "no default light" "no light source" render "$NOLIGHT" -o "$TMP/x.pfm" --no-default-light
expect_error "check: environment missing" "missing\.exr: no such file" check "$BOX" --environment "$TMP/missing.exr"
expect_error "converge: environment missing" "missing\.exr: no such file" converge "$BOX" -o "$TMP/conv-env" \
  --environment "$TMP/missing.exr"

# converge caches its reference by scene, settings, budget and environment: another environment
# renders a new reference instead of reusing one lit differently.
ENVSCENE="$SRC/tests/scenes/environment.gltf"
for env in "" "--environment=0.5,0.5,0.5" "--environment=0.5,0.5,0.5"; do
  "$PATHLAB" converge "$ENVSCENE" -o "$TMP/conv-key" --spp 2 --reference-spp 2 --width 8 --height 8 --force $env \
    >/dev/null 2>&1 || fail "converge $env"
done
[ "$(ls "$TMP/conv-key" | grep -c '^reference-.*\.exr$')" -eq 2 ] && ok || fail "reference keys: $(ls "$TMP/conv-key")"

echo "cli: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
