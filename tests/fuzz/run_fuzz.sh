#!/usr/bin/env bash
# Fuzz for SECONDS each (default 60) with clang's libFuzzer under ASan + UBSan: the glTF loader
# (seeded with every bundled and test scene), the image decoders (EXR, PFM, Radiance HDR; seeded
# with the bundled sky and small files of each format) and the presets reader (seeded with the
# shipped presets). Exit 0 when nothing was found; a crash leaves its input in
# BUILD/fuzz-artifacts/ — copy it to tests/scenes/bad/ (a scene) with a name saying what it is.
#   tests/fuzz/run_fuzz.sh [SECONDS] [BUILD_DIR] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/../.."
SECONDS_TO_RUN=${1:-60}
BUILD=${2:-build-fuzz}
shift $(( $# < 2 ? $# : 2 ))
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(gltf_loader_fuzz image_decoder_fuzz presets_fuzz)
if ! command -v clang++ >/dev/null; then echo "run_fuzz.sh: clang++ is missing (apt install clang libclang-rt-14-dev)" >&2; exit 1; fi
[ -f "$BUILD/CMakeCache.txt" ] || CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPATHLAB_FUZZ=ON -DPATHLAB_BUILD_TESTS=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$BUILD" -j "$(nproc)" --target "${TARGETS[@]}"
mkdir -p "$BUILD/fuzz-artifacts"

seed() {  # seed TARGET: the corpus folder, filled with the target's seeds
  local corpus="$BUILD/fuzz-corpus/$1"
  mkdir -p "$corpus"
  case $1 in
    gltf_loader_fuzz) cp -n assets/*.gltf tests/scenes/*.gltf tests/scenes/*.glb tests/scenes/bad/* "$corpus"/ 2>/dev/null || true ;;
    image_decoder_fuzz)
      cp -n assets/*.hdr tests/image/bad/* "$corpus"/ 2>/dev/null || true
      python3 - "$corpus" <<'PY'
import struct, sys
d = sys.argv[1]
open(d + "/small.pfm", "wb").write(b"PF\n2 2\n-1.0\n" + struct.pack("<12f", *range(12)))
line = bytes([2, 2, 0, 8]) + bytes([128 + 8, 100]) * 3 + bytes([8]) + bytes(range(128, 136))
open(d + "/rle.hdr", "wb").write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 8\n" + line * 2)
open(d + "/flat.hdr", "wb").write(b"#?RGBE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 2\n" + b"\x80\x40\x20\x81" * 4)
PY
      # A small EXR written by pathlab itself, when the release build is there to write one.
      [ -x build/app/pathlab ] && build/app/pathlab render assets/cornell-box.gltf -o "$corpus/small.exr" --spp 1 \
        --width 8 --height 6 --force >/dev/null 2>&1 || true ;;
    presets_fuzz) cp -n assets/presets.json "$corpus"/ 2>/dev/null || true ;;
  esac
  echo "$corpus"
}

for target in "${TARGETS[@]}"; do
  corpus=$(seed "$target")
  echo "run_fuzz.sh: $target for $SECONDS_TO_RUN s"
  # Embree allocates per scene; leaks are checked, but a slow input is not a bug here.
  ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp" "$BUILD/tests/fuzz/$target" "$corpus" -max_total_time="$SECONDS_TO_RUN" \
    -timeout=20 -rss_limit_mb=4096 -max_len=65536 -artifact_prefix="$BUILD/fuzz-artifacts/$target-" -print_final_stats=1
done
