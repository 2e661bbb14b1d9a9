#!/usr/bin/env bash
# The tests under AddressSanitizer + UndefinedBehaviorSanitizer and under ThreadSanitizer (issue
# 6), each in a build directory of its own, configured once like build/:
#   - ASan + UBSan: every test but the long statistical renders, whose arithmetic the release
#     suite already checks; the viewer's headless tests included (Mesa runs uninstrumented).
#   - TSan: the tests where threads meet (progressive renderer, its destruction mid-pass
#     included; sessions, reproducible at any thread count; film) and the viewer's
#     headless tests (`pathlab view --headless`: UI, render and scene loader threads; Mesa's
#     llvmpipe runs uninstrumented, see tsan.supp), with TBB serial
#     (tests/support/serial_tbb_under_tsan.cpp, linked into the test binaries and, under TSan, pathlab):
#     the tests where threads meet are a binary of their own there, pathlab_thread_tests.
# Usage: tests/sanitize/run_sanitizers.sh [address|thread|all]
set -euo pipefail
cd "$(dirname "$0")/../.."
which=${1:-all}
jobs=$(nproc)
supp=$PWD/tests/sanitize

configure() {  # DIR SANITIZER
  [ -f "$1/CMakeCache.txt" ] || cmake -S . -B "$1" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPATHLAB_SANITIZE="$2" >/dev/null
}

if [ "$which" = address ] || [ "$which" = all ]; then
  configure build-asan address
  cmake --build build-asan -j "$jobs" --target pathlab pathlab_tests pathlab_viewer_tests pathlab_cli_tests
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  # The long statistical renders (their arithmetic is the release suite's; each is 10-85 s here).
  slow='bench_smoke|converge_cli|TechniqueCheckRender|BundledAgreement|TechniqueAgreement|DeltaAgreement|Extremes|ScaleInvariance|ChiSquare'
  slow+='|RelMseSplit|MergeBiasRender|NaiveBptAgreement|EnvironmentAgreement|VertexMerging[.].*Agree'
  # tinyexr's own leak on corrupt pixel data (tests/fuzz/lsan.supp says why) is suppressed here as
  # in the fuzz stage: the image decoder tests feed it such files.
  ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan.supp \
    ctest --test-dir build-asan --output-on-failure -j "$jobs" -E "$slow|^viewer[.]"
  # Mesa's driver is unloaded before exit, leaving a few allocations LeakSanitizer can only
  # attribute to an "<unknown module>": the viewer runs with leak checking off, the rest of
  # ASan and UBSan on.
  ASAN_OPTIONS=detect_leaks=0 ctest --test-dir build-asan --output-on-failure -j "$jobs" -R '^viewer[.]'
fi

if [ "$which" = thread ] || [ "$which" = all ]; then
  configure build-tsan thread
  cmake --build build-tsan -j "$jobs" --target pathlab_thread_tests pathlab pathlab_viewer_tests
  # halt_on_error: the first report fails the test (exit code 66, also from the `pathlab view`
  # processes the viewer's tests start, which inherit TSAN_OPTIONS). Suppressions: tsan.supp (only
  # uninstrumented libraries: TBB, Embree, Mesa's llvmpipe driver), never pathlab's own code.
  export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$supp/tsan.supp"
  build-tsan/tests/pathlab_thread_tests \
    --gtest_filter='ProgressiveRenderer*:RenderSession*:TechniquePyramid.WeightedShares*:Film*:RenderSettingsValidation*:ErrorTracker.*:TechniqueCounters.Timing*'
  # The viewer's tests, headless (EGL on llvmpipe): its UI thread, render thread (TBB serial, also
  # in the pathlab binary) and scene loader thread. Not viewer.window: GLFW and Xvfb are the
  # release suite's. One at a time: as fast as two at once on these machines (about 45 s), and a
  # drop test that expects a scene to load within a few frames keeps its margin.
  # The aspect tests (geometry of the letterboxed image, no thread of their own) are the release
  # and ASan stages'. So are the environment's variants of one restart (a map dropped through the
  # scene loader thread stays here) and the error view's picture (its two series stay): the same
  # threads meeting the same way, 10-20 s each under TSan; so is the ppm box of the merge controls
  # (a settings edit like any other).
  tsanSame='ViewerAspect|ViewerMergeControls|ViewerEnvironment[.](NextEvent|AUniform|StrengthZero|TurningAOneSided)|ViewerError[.]ErrorView'
  ctest --test-dir build-tsan --output-on-failure -j 1 -R '^viewer[.]' -E "^viewer[.](window\$|.*($tsanSame))"
fi
