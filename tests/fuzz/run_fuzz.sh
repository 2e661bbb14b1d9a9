#!/usr/bin/env bash
# Fuzz the glTF loader for SECONDS (default 60) with clang's libFuzzer under ASan + UBSan, seeded
# with every bundled and test scene. Exit 0 when nothing was found; a crash leaves its input in
# BUILD/fuzz-artifacts/ — copy it to tests/scenes/bad/ with a name saying what it is.
#   tests/fuzz/run_fuzz.sh [SECONDS] [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
SECONDS_TO_RUN=${1:-60}
BUILD=${2:-build-fuzz}
if ! command -v clang++ >/dev/null; then echo "run_fuzz.sh: clang++ is missing (apt install clang libclang-rt-14-dev)" >&2; exit 1; fi
[ -f "$BUILD/CMakeCache.txt" ] || CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPATHLAB_FUZZ=ON -DPATHLAB_BUILD_TESTS=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$BUILD" -j "$(nproc)" --target gltf_loader_fuzz
corpus="$BUILD/fuzz-corpus"
mkdir -p "$corpus" "$BUILD/fuzz-artifacts"
cp -n assets/*.gltf tests/scenes/*.gltf tests/scenes/*.glb tests/scenes/bad/* "$corpus"/ 2>/dev/null || true
# Embree allocates per scene; leaks are checked, but a slow input is not a bug here.
ASAN_OPTIONS=detect_leaks=1 "$BUILD/tests/fuzz/gltf_loader_fuzz" "$corpus" -max_total_time="$SECONDS_TO_RUN" \
  -timeout=20 -rss_limit_mb=4096 -max_len=65536 -artifact_prefix="$BUILD/fuzz-artifacts/" -print_final_stats=1
