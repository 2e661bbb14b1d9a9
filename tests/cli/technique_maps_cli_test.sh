#!/bin/bash
# `pathlab render --technique-maps L` end to end: the files appear next to the output, an existing
# one is never overwritten without --force (and nothing is rendered then), and bad requests get one
# line and a non-zero exit.
. "$(dirname "$0")/cli_lib.sh"
BOX="$SRC/assets/cornell-box.gltf"
small=(--spp 2 --width 16 --height 12 --max-length 3)

if "$PATHLAB" render "$BOX" -o "$TMP/m.exr" "${small[@]}" --technique-maps 2 2>"$TMP/err"; then
  # k = 0..2: 3 dominant maps (EXR + PNG); 5 techniques: share and cannot EXRs; 2 mosaics.
  count=$(ls "$TMP" | grep -c '^m-')
  [ "$count" -eq 18 ] && [ -s "$TMP/m-dominant.png" ] && [ -s "$TMP/m-dominant-k2.exr" ] &&
    [ -s "$TMP/m-share-s1-t2.exr" ] && [ -s "$TMP/m-cannot-s0-t3.exr" ] && [ -s "$TMP/m-share.png" ] &&
    [ -s "$TMP/m-cannot-sample.png" ] && [ ! -e "$TMP/m-pyramid.png" ] && ok || fail "map files: $(ls "$TMP")"
  ls -a "$TMP" | grep -q '\.tmp' && fail "temporary files left behind: $(ls -a "$TMP")"
else fail "maps render: $(cat "$TMP/err")"; fi

# With merges (--integrator vcm) the maps cover them: M(2,2), the one merge up to length 2, gets its
# share and cannot-sample files beside the connections' (k = 0..2: 6 dominant files; 6 techniques;
# the two mosaics; the merges' share together as EXR and PNG).
if "$PATHLAB" render "$BOX" -o "$TMP/v.exr" "${small[@]}" --integrator vcm --technique-maps 2 2>"$TMP/err"; then
  count=$(ls "$TMP" | grep -c '^v-')
  [ "$count" -eq 22 ] && [ -s "$TMP/v-share-m-s2-t2.exr" ] && [ -s "$TMP/v-cannot-m-s2-t2.exr" ] &&
    [ -s "$TMP/v-share-merges.png" ] && [ -s "$TMP/v-share-merges.exr" ] &&
    [ -s "$TMP/v-dominant-k2.png" ] && ok || fail "vcm map files: $(ls "$TMP")"
else fail "vcm maps render: $(cat "$TMP/err")"; fi

# An existing map refuses the render (before any work) and leaves every file as it was.
before=$(md5sum "$TMP/m-dominant.png")
rm "$TMP/m.exr"
expect_error "map file exists" "m-dominant.exr: file exists" render "$BOX" -o "$TMP/m.exr" "${small[@]}" --technique-maps 2
[ -e "$TMP/m.exr" ] && fail "the image was written although a map exists"
[ "$(md5sum "$TMP/m-dominant.png")" = "$before" ] && ok || fail "an existing map was changed"
"$PATHLAB" render "$BOX" -o "$TMP/m.exr" "${small[@]}" --technique-maps 2 --force 2>"$TMP/err" && ok || fail "--force: $(cat "$TMP/err")"

expect_error "maps with pt" "technique-maps.*bpt" render "$BOX" -o "$TMP/x.exr" --integrator pt --technique-maps 2
expect_error "maps longer than the paths" "technique-maps 3 is longer" render "$BOX" -o "$TMP/x.exr" --max-length 2 --technique-maps 3
expect_error "maps absurd length" "technique-maps" render "$BOX" -o "$TMP/x.exr" --technique-maps 1000
expect_error "maps not a number" "technique-maps" render "$BOX" -o "$TMP/x.exr" --technique-maps k
mkdir "$TMP/m2-share.png"
expect_error "map target is a directory" "m2-share.png: is a directory" render "$BOX" -o "$TMP/m2.exr" "${small[@]}" --technique-maps 2

# The variance maps (issue 34): an EXR per technique up to the length (5 up to length 2), the
# mosaic and the dominant variance map as EXR and PNG; the variance is a second moment minus a
# squared mean, never negative; refused without independent bidirectional samples.
if "$PATHLAB" render "$BOX" -o "$TMP/var.exr" "${small[@]}" --variance-maps 2 2>"$TMP/err"; then
  count=$(ls "$TMP" | grep -c '^var-')
  [ "$count" -eq 8 ] && [ -s "$TMP/var-variance-s1-t2.exr" ] && [ -s "$TMP/var-variance.png" ] &&
    [ -s "$TMP/var-variance-dominant.exr" ] && [ -s "$TMP/var-variance-dominant.png" ] && ok ||
    fail "variance map files: $(ls "$TMP" | grep '^var-')"
else fail "variance maps render: $(cat "$TMP/err")"; fi
expect_error "variance maps with mlt" "variance-maps needs independent bidirectional samples" render "$BOX" \
  -o "$TMP/x.exr" --integrator mlt --variance-maps 2
expect_error "variance maps with pt" "variance-maps needs" render "$BOX" -o "$TMP/x.exr" --integrator pt --variance-maps 2
expect_error "variance maps longer than the paths" "variance-maps 3 is longer" render "$BOX" -o "$TMP/x.exr" \
  --max-length 2 --variance-maps 3

# Where the Metropolis chains spent their time (--chain-density): the values and the colours next
# to the output; refused without mlt.
if "$PATHLAB" render "$BOX" -o "$TMP/chains.exr" "${small[@]}" --integrator mlt --bootstrap 500 --chains 20 \
     --chain-density 2>"$TMP/err"; then
  [ -s "$TMP/chains-chain-density.exr" ] && [ -s "$TMP/chains-chain-density.png" ] && ok ||
    fail "chain density files: $(ls "$TMP" | grep '^chains')"
else fail "mlt --chain-density: $(cat "$TMP/err")"; fi
expect_error "chain density without mlt" "use it with --integrator mlt" render "$BOX" -o "$TMP/x.exr" --chain-density
rm -f "$TMP/chains.exr"
expect_error "chain density file exists" "chains-chain-density.exr: file exists" render "$BOX" -o "$TMP/chains.exr" \
  "${small[@]}" --integrator mlt --chain-density
[ -e "$TMP/chains.exr" ] && fail "the image was written although the density file exists"

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
