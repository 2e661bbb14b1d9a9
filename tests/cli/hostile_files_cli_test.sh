#!/usr/bin/env bash
# Issue 37, end to end: every file pathlab opens goes through the guarded reader (a FIFO fails in
# one line, never hangs), image headers cannot make it allocate or loop, products that overflow
# after loading are refused, presets are checked as the CLI checks options, and messages name the
# option the user typed. Each refusal: one line, non-zero exit, within CLI_DEADLINE seconds.
source "$(dirname "$0")/cli_lib.sh"
CLI_DEADLINE=20

BOX="$SRC/assets/cornell-box.gltf"
SHOT=(--headless --frames 1 --screenshot "$TMP/shot.png" --force)
mkfifo "$TMP/fifo.json" "$TMP/fifo.exr" "$TMP/fifo.hdr" "$TMP/fifo.gltf"

# Special files, by every option that names a file.
expect_error "view --presets FIFO" "fifo.json: .*is a FIFO, not a regular file" view "$BOX" "${SHOT[@]}" --presets "$TMP/fifo.json"
expect_error "view --reference FIFO" "fifo.exr: is a FIFO, not a regular file" view "$BOX" "${SHOT[@]}" --reference "$TMP/fifo.exr"
expect_error "converge --reference FIFO" "fifo.exr: is a FIFO, not a regular file" \
  converge "$BOX" -o "$TMP/conv" --time 0.1 --reference "$TMP/fifo.exr"
expect_error "render --environment FIFO" "fifo.hdr: is a FIFO, not a regular file" render "$BOX" -o "$TMP/x.png" --environment "$TMP/fifo.hdr"
expect_error "render scene FIFO" "fifo.gltf: .*FIFO" render "$TMP/fifo.gltf" -o "$TMP/x.png"
expect_error "view --presets directory" "is a directory, not a regular file" view "$BOX" "${SHOT[@]}" --presets "$TMP"

# Image headers that lie, truncated data.
python3 - "$TMP" <<'PY'
import struct, sys
tmp = sys.argv[1]
def hdr(w, h, data): return b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w) + data
# Run-length scanlines of 512 texels, cut in the middle of one (stb_image 2.27 loops forever on it).
line = bytes([2, 2, 2, 0]) + ((bytes([128]) + bytes([100]) * 128) * 4) * 4  # literal runs of 128
open(tmp + "/cut-rle.hdr", "wb").write(hdr(512, 16, line * 16)[:-9])
open(tmp + "/cut-flat.hdr", "wb").write(hdr(64, 32, b"\x80\x80\x80\x81" * (64 * 32 - 1)))
open(tmp + "/claims.hdr", "wb").write(hdr(16384, 8192, b""))
# The brightest RGBE texel (1.7e38) fits a float; times --environment-strength 1e6 it does not.
open(tmp + "/bright.hdr", "wb").write(hdr(8, 4, b"\xff\xff\xff\xff" * 32))
open(tmp + "/claims.pfm", "wb").write(b"PF\n60000 60000\n-1.0\n" + struct.pack("<3f", 1, 1, 1))
open(tmp + "/cut.pfm", "wb").write(b"PF\n10000 10000\n-1.0\n" + struct.pack("<3f", 1, 1, 1) * 100)
open(tmp + "/maxlength.json", "w").write('{"presets": [{"name": "wrap", "maxLength": 4294967300}]}')
open(tmp + "/eye.json", "w").write('{"presets": [{"name": "far", "camera": {"eye": [1e39, 0, 0], "target": [0, 0, 0]}}]}')
PY
start=$(date +%s)
expect_error "truncated RLE .hdr" "cut-rle.hdr: cannot read the HDR image \(truncated" render "$BOX" -o "$TMP/x.png" --environment "$TMP/cut-rle.hdr"
expect_error "truncated flat .hdr" "cut-flat.hdr: cannot read the HDR image \(truncated" render "$BOX" -o "$TMP/x.png" --environment "$TMP/cut-flat.hdr"
expect_error ".hdr claiming 16384x8192" "claims.hdr: the HDR header claims 16384x8192 texels.*truncated" \
  render "$BOX" -o "$TMP/x.png" --environment "$TMP/claims.hdr"
expect_error "PFM reference claiming 60000x60000" "claims.pfm: the PFM header claims 60000x60000 texels, more than" \
  converge "$BOX" -o "$TMP/conv" --time 0.1 --reference "$TMP/claims.pfm"
expect_error "PFM reference claiming 10000x10000" "cut.pfm: the PFM header claims 10000x10000 texels.*truncated" \
  view "$BOX" "${SHOT[@]}" --reference "$TMP/cut.pfm"
[ $(($(date +%s) - start)) -lt 10 ] && ok || fail "the image refusals took $(($(date +%s) - start)) s"

# Products that overflow after loading.
expect_error "environment strength x texels" "bright.hdr: radiance up to .* x --environment-strength 1e\+06 overflows" \
  render "$BOX" -o "$TMP/x.png" --environment "$TMP/bright.hdr" --environment-strength 1e6

# Presets checked as the CLI checks options, naming the file and the preset.
expect_error "presets maxLength wraps" "maxlength.json: preset 0 \(\"wrap\"\): \"maxLength\" must be in \[1, 1000\], not 4294967300" \
  view "$BOX" "${SHOT[@]}" --presets "$TMP/maxlength.json"
expect_error "presets eye 1e39" "eye.json: preset 0 \(\"far\"\): camera eye 1e\+39 is not a finite" \
  view "$BOX" "${SHOT[@]}" --presets "$TMP/eye.json"

# Messages that name the option typed.
expect_error "view --compare garbage" "^pathlab: --compare: 'garbage': unknown integrator" view "$BOX" "${SHOT[@]}" --compare garbage
expect_error "check --inject-bias 9,9" "--inject-bias 9,9,1.05: technique \(9,9\) has length 17" check "$BOX" --inject-bias 9,9,1.05
expect_error "render --isolate 9,9" "--isolate 9,9: technique \(9,9\) has length 17" render "$BOX" -o "$TMP/x.png" --isolate 9,9

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
