#!/usr/bin/env bash
# Sets up, builds and runs every test: the README's test command, and what CI runs.
#
#   1. installs missing Debian packages (scripts/install-deps.sh, idempotent);
#   2. builds everything in build/ with warnings as errors and runs all tests (unit, cli, render);
#   3. builds again in build-asan/ with AddressSanitizer + UndefinedBehaviorSanitizer and runs
#      the tests once more (all but the render tests);
#   4. builds the libFuzzer targets of fuzz/ with clang and runs each for a short fixed time
#      (scripts/fuzz.sh; FREEFORM_SKIP_FUZZ=1 skips it).
# Render tests need an X display: when there is none, the whole run goes under xvfb-run.
set -euo pipefail
cd "$(dirname "$0")/.."

if [ -z "${FREEFORM_UNDER_XVFB:-}" ]; then
  scripts/install-deps.sh
fi
if [ -z "${DISPLAY:-}" ] && [ -z "${FREEFORM_UNDER_XVFB:-}" ] && command -v xvfb-run >/dev/null; then
  export FREEFORM_UNDER_XVFB=1
  exec xvfb-run -a -s "-screen 0 1280x800x24" "$0" "$@"
fi

jobs=$(nproc 2>/dev/null || echo 2)
# ccache, when the machine has it, makes a second run of this script on unchanged sources fast; it is
# not a dependency (a fresh machine builds without it). Paths are hashed relative to the checkout,
# so two clones in different folders share the cache.
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(cd .. && pwd)}"
fi

echo "== build (Release, -Werror)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DFREEFORM_WARNINGS_AS_ERRORS=ON "${launcher[@]}" >/dev/null
cmake --build build -j "$jobs"
echo "== tests"
ctest --test-dir build --output-on-failure -j "$jobs"

if [ "${FREEFORM_SKIP_SANITIZERS:-}" != "1" ]; then
  echo "== build (AddressSanitizer + UndefinedBehaviorSanitizer)"
  # -O1 without debug info keeps the instrumented build of the template-heavy tests within CI's
  # time on two cores. The editor's unit tests (scene, history, interaction, tools) run here too;
  # its render tests (label "render") run in the main build only (llvmpipe under ASan is slow and
  # its JIT reports leaks of its own).
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1" -DFREEFORM_SANITIZE=ON \
        -DFREEFORM_WARNINGS_AS_ERRORS=ON -DFREEFORM_BUILD_BENCHMARKS=OFF -DFREEFORM_BUILD_EDITOR=ON "${launcher[@]}" >/dev/null
  cmake --build build-asan -j "$jobs"
  echo "== tests under sanitizers"
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j "$jobs" -LE render
fi
if [ "${FREEFORM_SKIP_FUZZ:-}" != "1" ]; then
  echo "== fuzzing (scripts/fuzz.sh: every reader, ${FREEFORM_FUZZ_SECONDS:-10} s each, ASan + UBSan)"
  scripts/fuzz.sh
fi
echo "== all tests passed"
