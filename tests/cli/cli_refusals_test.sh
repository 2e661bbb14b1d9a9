#!/usr/bin/env bash
# Issue 18, classes 3 and 4, end to end: non-finite numbers and unwritable outputs are refused by
# every subcommand before any work, with one line naming the option or path and a non-zero exit.
# (tests/cli/ walks every numeric option in-process; this runs the real binary.)
source "$(dirname "$0")/cli_lib.sh"

BOX="$SRC/assets/cornell-box.gltf"
# A scene that does not exist: an output refusal that names the output, not the scene, was made
# before loading.
NONE="$TMP/no-such-scene.gltf"

# Non-finite numbers, option by option and subcommand by subcommand.
expect_error "render --time nan" "--time.*nan" render "$BOX" -o "$TMP/x.png" --time nan
expect_error "render --exposure inf" "--exposure.*inf" render "$BOX" -o "$TMP/x.png" --exposure inf
expect_error "render --aperture nan" "--aperture.*nan" render "$BOX" -o "$TMP/x.png" --aperture nan
expect_error "render --focus-distance 1e999" "--focus-distance.*1e999" render "$BOX" -o "$TMP/x.png" --focus-distance 1e999
expect_error "render --beta=-inf" "--beta.*-inf" render "$BOX" -o "$TMP/x.png" --beta=-inf
expect_error "render --min-connection nan" "--min-connection.*nan" render "$BOX" -o "$TMP/x.png" --min-connection nan
expect_error "render --seed nan" "--seed.*nan" render "$BOX" -o "$TMP/x.png" --seed nan
expect_error "view --exposure nan" "--exposure.*nan" view "$BOX" --exposure nan
expect_error "view --beta inf" "--beta.*inf" view "$BOX" --beta inf
expect_error "view --render-scale nan" "--render-scale.*nan" view "$BOX" --render-scale nan
expect_error "converge --time nan" "--time.*nan" converge "$BOX" -o "$TMP/conv" --time nan
expect_error "converge --reference-time inf" "--reference-time.*inf" converge "$BOX" -o "$TMP/conv" --reference-time inf
expect_error "converge --checkpoint-factor nan" "--checkpoint-factor.*nan" converge "$BOX" -o "$TMP/conv" --checkpoint-factor nan
# Numbers inside text options are checked where they are parsed.
expect_error "converge beta=nan" "beta=nan" converge "$BOX" -o "$TMP/conv" --configs "bpt:beta=nan"
expect_error "converge min-connection=inf" "min-connection=inf" converge "$BOX" -o "$TMP/conv" --configs "bpt:min-connection=inf"
expect_error "render --isolate nan" "--isolate.*nan" render "$BOX" -o "$TMP/x.png" --isolate nan,1
expect_error "render --replay nan" "--replay.*nan" render "$BOX" --replay 1,nan,0
[ ! -e "$TMP/conv" ] && ok || fail "a refused converge created its output directory"

# Outputs that cannot be written, refused before the scene is loaded.
mkdir "$TMP/dir.png" "$TMP/conv-dir" "$TMP/conv-dir/convergence.csv" "$TMP/pyr-s0-t2.pfm"
mkfifo "$TMP/fifo.pfm"
touch "$TMP/plain-file"
expect_error "render -o /proc" "/proc/pathlab.png: .*pseudo file system" render "$NONE" -o /proc/pathlab.png
expect_error "render -o a directory" "dir.png: is a directory" render "$NONE" -o "$TMP/dir.png"
expect_error "render -o /tmp" "/tmp: is a directory" render "$NONE" -o /tmp
expect_error "render -o missing parent" "x.png: the directory .*/missing does not exist" render "$NONE" -o "$TMP/missing/x.png"
expect_error "render -o under a file" "plain-file is not a directory" render "$NONE" -o "$TMP/plain-file/x.png"
expect_error "render -o a FIFO" "fifo.pfm: is not a regular file" render "$NONE" -o "$TMP/fifo.pfm" --force
expect_error "render -o /dev/null" "/dev/null: is not a regular file" render "$NONE" -o /dev/null --force
expect_error "render pyramid image a directory" "pyr-s0-t2.pfm: is a directory" render "$NONE" -o "$TMP/pyr.pfm" --pyramid 2
expect_error "converge -o /proc" "/proc/pathlab-results: .*pseudo file system" converge "$NONE" -o /proc/pathlab-results
expect_error "converge -o a file" "plain-file: exists and is not a directory" converge "$NONE" -o "$TMP/plain-file"
expect_error "converge -o missing parent" "the directory .*/missing does not exist" converge "$NONE" -o "$TMP/missing/results"
expect_error "converge CSV a directory" "convergence.csv: is a directory" converge "$NONE" -o "$TMP/conv-dir" --force
expect_error "view --screenshot /proc" "/proc/shot.png: .*pseudo file system" view "$NONE" --headless --frames 1 --screenshot /proc/shot.png
expect_error "view --screenshot a directory" "dir.png: is a directory" view "$NONE" --headless --frames 1 --screenshot "$TMP/dir.png"
expect_error "view --error-csv missing parent" "errors.csv: the directory .*/missing does not exist" \
  view "$NONE" --reference "$TMP/ref.exr" --error-csv "$TMP/missing/errors.csv"

# Vertex merging: vcm and bpm set their own techniques; what merging cannot do yet is refused.
expect_error "render --integrator vcm --techniques" "--integrator vcm sets the techniques" \
  render "$BOX" -o "$TMP/x.png" --integrator vcm --techniques all
expect_error "render --radius 0" "--radius" render "$BOX" -o "$TMP/x.png" --integrator vcm --radius 0
expect_error "render --noncaustic-photons 0" "--noncaustic-photons" render "$BOX" -o "$TMP/x.png" --integrator vcm --noncaustic-photons 0
expect_error "converge vcm:noncaustic-photons=2" "noncaustic-photons 2" converge "$BOX" -o "$TMP/conv" --configs "vcm:noncaustic-photons=2" --spp 2
expect_error "render --medium-sampling sideways" "--medium-sampling" render "$BOX" -o "$TMP/x.png" --medium-sampling sideways
expect_error "render lt --medium-sampling mis" "the lt integrator samples distances" render "$BOX" -o "$TMP/x.png" --integrator lt --medium-sampling mis
expect_error "render vcm --medium-sampling mis" "merging techniques' weights do not count" render "$BOX" -o "$TMP/x.png" --integrator vcm --medium-sampling mis
expect_error "render mlt --medium-sampling mis" "the mlt integrator samples distances" render "$BOX" -o "$TMP/x.png" --integrator mlt --medium-sampling mis
expect_error "render naive bpt --medium-sampling mis" "needs path reuse" render "$BOX" -o "$TMP/x.png" --connect endpoints --medium-sampling mis
expect_error "converge medium-sampling=x" "unknown medium sampling 'x'" converge "$BOX" -o "$TMP/conv" --configs "pt:medium-sampling=x" --spp 2
expect_error "converge lt:medium-sampling=equiangular" "the lt integrator samples distances" converge "$BOX" -o "$TMP/conv" --configs "lt:medium-sampling=equiangular" --spp 2
# Metropolis (issue 33): its options apply to mlt only, in range; what needs independent samples per
# pixel is refused with it.
expect_error "render --chains without mlt" "--chains applies to --integrator mlt" render "$BOX" -o "$TMP/x.png" --chains 10
expect_error "render --sigma 0" "--sigma" render "$BOX" -o "$TMP/x.png" --integrator mlt --sigma 0
expect_error "render --large-step 2" "--large-step" render "$BOX" -o "$TMP/x.png" --integrator mlt --large-step 2
expect_error "render --mlt-variant kelemen" "--mlt-variant" render "$BOX" -o "$TMP/x.png" --integrator mlt --mlt-variant kelemen
expect_error "render mlt with merges" "mlt runs over connections" render "$BOX" -o "$TMP/x.png" --integrator mlt --techniques "all;m=all"
expect_error "render mlt --pyramid" "technique pyramid needs the bpt or lt" render "$BOX" -o "$TMP/x.png" --integrator mlt --pyramid 2
expect_error "render mlt --replay" "--replay replays one independent sample" render "$BOX" --integrator mlt --replay 1,1,0
expect_error "render --mutations-per-pixel with bpt" "--mutations-per-pixel applies to --integrator mlt" \
  render "$BOX" -o "$TMP/x.png" --mutations-per-pixel 4
expect_error "converge bpt:chains=4" "chains applies to mlt, not bpt" converge "$BOX" -o "$TMP/conv" --configs "bpt:chains=4" --spp 2
expect_error "converge mlt:mlt-variant=x" "unknown MLT variant 'x'" converge "$BOX" -o "$TMP/conv" --configs "mlt:mlt-variant=x" --spp 2
"$PATHLAB" render "$BOX" -o "$TMP/mlt.exr" --integrator mlt --mutations-per-pixel 2 --bootstrap 1000 --chains 16 --width 16 \
  --height 16 --force >/dev/null 2>"$TMP/mlt.err" && [ -s "$TMP/mlt.exr" ] && ok || fail "render --integrator mlt"
# Its summary: b with its standard error, the acceptance, and the chains per length.
grep -qE "^mlt \(mmlt\): b = [0-9.e+-]+ \+- [0-9.e+-]+ \([0-9.]+ %, from 1000 bootstrap samples per length and the large steps\), [0-9]+ chains" "$TMP/mlt.err" &&
  grep -qE "^ +2 +[0-9]+ +[0-9.]+ %$" "$TMP/mlt.err" && ok || fail "render --integrator mlt summary: $(cat "$TMP/mlt.err")"
# The short paths by BPT beside the chains (--mlt-direct): within the maximum length, mlt only,
# and the summary says so.
expect_error "render --mlt-direct 11" "--mlt-direct 11 is outside 0..10" render "$BOX" -o "$TMP/x.png" --integrator mlt --mlt-direct 11
expect_error "render --mlt-direct with bpt" "--mlt-direct applies to --integrator mlt" render "$BOX" -o "$TMP/x.png" --mlt-direct 1
expect_error "converge bpt:mlt-direct=1" "mlt-direct applies to mlt, not bpt" converge "$BOX" -o "$TMP/conv" --configs "bpt:mlt-direct=1" --spp 2
"$PATHLAB" render "$BOX" -o "$TMP/mlt-direct.exr" --integrator mlt --mlt-direct 2 --mutations-per-pixel 2 --bootstrap 1000 \
  --chains 16 --width 16 --height 16 --force >/dev/null 2>"$TMP/mlt-direct.err" &&
  grep -qE "^  paths of up to 2 edges by BPT beside the chains: 2 samples per pixel$" "$TMP/mlt-direct.err" &&
  grep -qE "^ +2 +BPT +-$" "$TMP/mlt-direct.err" && ok || fail "render --mlt-direct 2 summary: $(cat "$TMP/mlt-direct.err")"
"$PATHLAB" render "$BOX" -o "$TMP/vcm.exr" --integrator vcm --spp 1 --width 16 --height 16 --force >/dev/null 2>&1 &&
  [ -s "$TMP/vcm.exr" ] && ok || fail "render --integrator vcm"

# With a real scene and a long budget the refusal still comes at once, not after the render.
start=$(date +%s)
expect_error "render -o /proc with a budget" "/proc/x.png" render "$BOX" -o /proc/x.png --time 20
[ $(($(date +%s) - start)) -lt 10 ] && ok || fail "the /proc refusal took $(($(date +%s) - start)) s"

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
