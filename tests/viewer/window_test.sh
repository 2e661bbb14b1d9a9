#!/usr/bin/env bash
# The real GLFW window, once, under a virtual X server: it opens, is resized, orbits and resets
# through scripted input, draws the panels and the image, and closes cleanly while rendering.
# Exit 77 (CTest: skipped) without xvfb-run.
set -u
PATHLAB=$1
SRC=$2
TMP=$3
command -v xvfb-run >/dev/null || { echo "xvfb-run not installed: skipped"; exit 77; }
mkdir -p "$TMP"
OUT="$TMP/window.png"
rm -f "$OUT"
timeout 120 xvfb-run -a -s "-screen 0 1280x800x24" "$PATHLAB" view "$SRC/assets/cornell-box.gltf" \
  --width 500 --height 300 --render-scale 0.25 --frames 24 --spp 1 --threads 2 --screenshot "$OUT" \
  --script '2:resize=800,500;4:resize=320,200;6:resize=640,400;8:drag=500,200>540,210;13:key=R' 2>"$TMP/window.err"
code=$?
cat "$TMP/window.err"
[ "$code" -eq 0 ] || { echo "FAIL: exit code $code"; exit 1; }
grep -q "window" "$TMP/window.err" || { echo "FAIL: did not run in a window"; exit 1; }
[ -s "$OUT" ] || { echo "FAIL: no screenshot"; exit 1; }
# PNG IHDR: width and height are big-endian at bytes 16..23.
size=$(od -An -tu1 -j16 -N8 "$OUT" | awk '{print $1*16777216+$2*65536+$3*256+$4 "x" $5*16777216+$6*65536+$7*256+$8}')
[ "$size" = "640x400" ] || { echo "FAIL: screenshot is $size, not 640x400"; exit 1; }
# Not a blank frame: more than a handful of distinct byte values in the image data.
distinct=$(od -An -tu1 -v "$OUT" | tr -s ' ' '\n' | sort -u | wc -l)
[ "$distinct" -gt 100 ] || { echo "FAIL: the screenshot looks blank"; exit 1; }
echo "ok: window $size"
