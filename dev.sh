#!/usr/bin/env bash
# pathlab set-up on Debian 12, idempotent and quick when nothing changed:
#   ./dev.sh run    install missing packages, build, open the viewer (render the default scene
#                   to out/cornell-box.png when there is no $DISPLAY)
#   ./dev.sh test   install missing packages, build, run the whole test suite: the Release tests,
#                   then the tests under ASan + UBSan and TSan and a 30 s fuzzing run of the
#                   glTF loader (clang), each in a build directory of its own
#   ./dev.sh check  the Release tests only (quick, while working)
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(g++ make cmake pkg-config python3
  libembree-dev libtbb-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libtinyexr-dev
  libcli11-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev libopenvdb-dev
  libglfw3-dev libimgui-dev libgl-dev libegl-dev libegl-mesa0 libgl1-mesa-dri fonts-dejavu-core xvfb xauth
  clang libclang-rt-14-dev
  libopenmpi-dev openmpi-bin
  pybind11-dev python3-dev python3-numpy python3-pytest
  python3-nbclient python3-nbformat python3-ipykernel python3-matplotlib)
BUILD_DIR=${PATHLAB_BUILD_DIR:-build}

install_packages() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return
  echo "dev.sh: installing ${missing[*]}" >&2
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

build() {
  [ -f "$BUILD_DIR/CMakeCache.txt" ] || cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release
  cmake --build "$BUILD_DIR" -j "$(nproc)"
}

case "${1:-}" in
  run)
    install_packages
    build
    if [ -n "${DISPLAY:-}" ]; then
      exec "$BUILD_DIR/app/pathlab" view assets/cornell-box.gltf --presets assets/presets.json
    fi
    # No display: render the default scene instead (the viewer also runs offscreen, see docs/viewer.md).
    mkdir -p out
    "$BUILD_DIR/app/pathlab" render assets/cornell-box.gltf -o out/cornell-box.png --spp 64 --force
    echo "dev.sh: no \$DISPLAY, so no viewer; wrote out/cornell-box.png" >&2
    ;;
  test)
    install_packages
    build
    ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)"
    tests/sanitize/run_sanitizers.sh all
    tests/fuzz/run_fuzz.sh 30
    ;;
  check)
    install_packages
    build
    ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)"
    ;;
  *)
    echo "usage: ./dev.sh run | ./dev.sh test | ./dev.sh check" >&2
    exit 2
    ;;
esac
