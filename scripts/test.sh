#!/usr/bin/env bash
# Sets up, builds and runs every test: the README's test command, and what CI runs.
#
#   1. installs missing Debian packages (scripts/install-deps.sh, idempotent);
#   2. builds everything in build/ with warnings as errors and runs all tests (unit, cli, render);
#   3. builds again in build-asan/ with AddressSanitizer + UndefinedBehaviorSanitizer and runs
#      the tests once more (all but the render tests);
#   4. builds the libFuzzer targets of fuzz/ with clang and runs each for a short fixed time
#      (scripts/fuzz.sh; FREEFORM_SKIP_FUZZ=1 skips it).
# Render tests need an X display: when there is none, the script starts Xvfb itself. It lets Xvfb
# pick a free display (-displayfd) instead of `xvfb-run -a`, whose pick (the first display without a
# lock file, then a separate start) races other X servers started on the same machine at the same
# time; a CI run once lost an editor's connection to its display that way.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
if [ -z "${DISPLAY:-}" ] && command -v Xvfb >/dev/null; then
  xvfb_dir=$(mktemp -d)
  Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp 3>"$xvfb_dir/display" >"$xvfb_dir/log" 2>&1 &
  xvfb_pid=$!
  trap 'kill "$xvfb_pid" 2>/dev/null; rm -rf "$xvfb_dir"' EXIT
  for _ in $(seq 100); do
    grep -q '^[0-9][0-9]*$' "$xvfb_dir/display" 2>/dev/null && break
    kill -0 "$xvfb_pid" 2>/dev/null || { cat "$xvfb_dir/log" >&2; echo "error: Xvfb did not start" >&2; exit 1; }
    sleep 0.1
  done
  grep -q '^[0-9][0-9]*$' "$xvfb_dir/display" || { echo "error: Xvfb gave no display in 10 s" >&2; exit 1; }
  export DISPLAY=":$(cat "$xvfb_dir/display")"
  echo "== Xvfb on display $DISPLAY"
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
