#!/usr/bin/env bash
# `pathlab render`'s image size follows the glTF camera's aspect ratio, so nothing the camera frames
# is cropped: neither --width nor --height gives the longest side 512 and the other side rounded to
# the nearest pixel (veach-mis, aspect 1.5: 512 x 341); one of them derives the other; both are
# taken exactly as given.
source "$(dirname "$0")/cli_lib.sh"

BOX="$SRC/assets/cornell-box.gltf"
VEACH="$SRC/assets/veach-mis.gltf"

# expect_size DESCRIPTION WIDTH HEIGHT ARGS...: renders a PFM (its header says "PF\nW H") and
# checks its size.
expect_size() {
  local what=$1 w=$2 h=$3
  shift 3
  rm -f "$TMP/size.pfm"
  if ! "$PATHLAB" render "$@" -o "$TMP/size.pfm" --spp 1 --max-length 2 2>"$TMP/err" </dev/null; then
    fail "$what: $(cat "$TMP/err")"
    return
  fi
  local size
  size=$(head -c 64 "$TMP/size.pfm" | sed -n 2p)
  if [ "$size" != "$w $h" ]; then fail "$what: the image is '$size', not '$w $h'"; return; fi
  ok
}

expect_size "cornell-box by default" 512 512 "$BOX"
expect_size "veach-mis by default" 512 341 "$VEACH"
expect_size "veach-mis --width 300" 300 200 "$VEACH" --width 300
expect_size "veach-mis --height 100" 150 100 "$VEACH" --height 100
expect_size "cornell-box --width 300" 300 300 "$BOX" --width 300
# Both given: exactly those, whatever the camera's aspect (as before).
expect_size "veach-mis --width 64 --height 64" 64 64 "$VEACH" --width 64 --height 64
expect_size "cornell-box --width 48 --height 36" 48 36 "$BOX" --width 48 --height 36
# A derived side counts towards the pixel limit too.
expect_error "derived side too many pixels" "pixels" render "$VEACH" -o "$TMP/x.pfm" --height 16384
# --replay is checked against the derived size.
expect_error "replay outside the derived size" "outside the 512 x 341" render "$VEACH" --replay 5,400,0 --max-length 2

# converge and check take the camera's shape too (longest side 256 and 128 unless given): the
# size is in converge's CSV-side efficiency table and on check's first line.
if "$PATHLAB" converge "$VEACH" --configs pt --spp 2 --max-length 2 -o "$TMP/conv" --force >"$TMP/out" 2>"$TMP/err" </dev/null &&
   grep -q "256 x 171" "$TMP/conv/efficiency.md"; then ok
else fail "converge veach-mis by default: not 256 x 171: $(cat "$TMP/err") $(head -5 "$TMP/conv/efficiency.md" 2>/dev/null)"; fi
"$PATHLAB" check "$VEACH" --spp 2 --max-length 2 >"$TMP/out" 2>"$TMP/err" </dev/null
if head -1 "$TMP/out" | grep -q "128 x 85"; then ok; else fail "check veach-mis by default: $(head -1 "$TMP/out") $(cat "$TMP/err")"; fi
"$PATHLAB" check "$VEACH" --spp 2 --max-length 2 --width 60 >"$TMP/out" 2>"$TMP/err" </dev/null
if head -1 "$TMP/out" | grep -q "60 x 40"; then ok; else fail "check veach-mis --width 60: $(head -1 "$TMP/out") $(cat "$TMP/err")"; fi

echo "render_size_cli: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
