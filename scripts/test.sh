#!/usr/bin/env bash
# Sets up, builds and runs every test: the README's test command, and what CI runs.
#
#   1. installs missing Debian packages (scripts/install-deps.sh, idempotent);
#   2. builds everything in build/ with g++, warnings as errors, and runs all tests (unit, cli,
#      render, python);
#   3. builds again in build-asan/ with clang, AddressSanitizer + UndefinedBehaviorSanitizer and
#      warnings as errors, and runs the tests once more (all but the render tests, which that build
#      leaves out). The same build holds the libFuzzer targets of fuzz/: the library is compiled
#      once, with libFuzzer's coverage instrumentation, for both;
#   4. runs each fuzz target for 5 s (scripts/fuzz.sh; FREEFORM_FUZZ_SECONDS sets another time,
#      FREEFORM_SKIP_FUZZ=1 skips it).
# FREEFORM_SKIP_SANITIZERS=1 skips stages 3 and 4. At its end (and when a stage fails) it prints the
# wall time of each stage, so every CI log shows where the time went (docs/development.md).
#
# Render tests need an X display: when there is none, the script starts Xvfb itself. It lets Xvfb
# pick a free display (-displayfd) instead of `xvfb-run -a`, whose pick (the first display without a
# lock file, then a separate start) races other X servers started on the same machine at the same
# time; a CI run once lost an editor's connection to its display that way.
set -euo pipefail
cd "$(dirname "$0")/.."

stages=()
stage_start=$SECONDS
script_start=$SECONDS
stage_name=""
# stage NAME: ends the stage that is running (recording its wall time) and starts NAME.
stage() {
  if [ -n "$stage_name" ]; then stages+=("$stage_name|$((SECONDS - stage_start))"); fi
  stage_name=$1
  stage_start=$SECONDS
  [ -n "$stage_name" ] && echo "== $stage_name"
  return 0
}
print_stages() {
  local status=$1
  if [ -n "$stage_name" ]; then
    stages+=("$stage_name$([ "$status" -ne 0 ] && echo ' (failed)')|$((SECONDS - stage_start))")
    stage_name=""
  fi
  echo "== stage times (wall clock)"
  printf '%-44s %8s\n' stage seconds
  local s
  for s in "${stages[@]}"; do printf '%-44s %8s\n' "${s%|*}" "${s##*|}"; done
  printf '%-44s %8s\n' total "$((SECONDS - script_start))"
}
cleanups=()
on_exit() {
  local status=$?
  print_stages "$status" || true
  local c
  for c in "${cleanups[@]}"; do eval "$c" || true; done
  exit $status
}
trap on_exit EXIT

stage "install (scripts/install-deps.sh)"
scripts/install-deps.sh

if [ -z "${DISPLAY:-}" ] && command -v Xvfb >/dev/null; then
  xvfb_dir=$(mktemp -d)
  Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp 3>"$xvfb_dir/display" >"$xvfb_dir/log" 2>&1 &
  xvfb_pid=$!
  cleanups+=("kill $xvfb_pid 2>/dev/null; rm -rf '$xvfb_dir'")
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
# Ninja when it is there (scripts/install-deps.sh installs it): it keeps both cores busy across
# targets and leaves a log of every step's time (build/.ninja_log).
generator=()
if command -v ninja >/dev/null; then generator=(-G Ninja); fi
# ccache, when the machine has it, makes a second run of this script on unchanged sources fast; it is
# not a dependency (a fresh machine builds without it). Paths are hashed relative to the checkout,
# so two clones in different folders share the cache.
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(cd .. && pwd)}"
  # Precompiled headers and ccache: the PCH's timestamps must not defeat the cache.
  export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime,include_file_ctime}"
fi
# A build folder configured with another generator cannot be reused: start it anew.
fresh_if_other_generator() {
  local dir=$1 want=Unix
  [ ${#generator[@]} -gt 0 ] && want=Ninja
  if [ -f "$dir/CMakeCache.txt" ] && ! grep -q "^CMAKE_GENERATOR:INTERNAL=$want" "$dir/CMakeCache.txt"; then
    rm -rf "$dir"
  fi
}

stage "build (g++ Release, -Werror)"
fresh_if_other_generator build
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DFREEFORM_WARNINGS_AS_ERRORS=ON "${launcher[@]}" >/dev/null
cmake --build build -j "$jobs"
stage "tests (Release)"
ctest --test-dir build --output-on-failure -j "$jobs"

if [ "${FREEFORM_SKIP_SANITIZERS:-}" != "1" ]; then
  stage "build (clang ASan+UBSan -O1, fuzz targets)"
  # One clang build serves the sanitizer tests and the fuzz targets (scripts/fuzz.sh configures
  # the same folder the same way). -O1 without debug info keeps it within CI's time on two cores.
  # The editor's unit tests (scene, history, interaction, tools) run here too; its render tests
  # (label "render") are built and run in the main build only (llvmpipe under ASan is slow and its
  # JIT reports leaks of its own).
  FREEFORM_FUZZ_CONFIGURE_ONLY=1 scripts/fuzz.sh
  cmake --build build-asan -j "$jobs"
  stage "tests (ASan+UBSan)"
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j "$jobs" -LE render
  if [ "${FREEFORM_SKIP_FUZZ:-}" != "1" ]; then
    # 5 s per target here (scripts/fuzz.sh alone: 10): the CAD work's builds took the 40 s back
    # (docs/development.md); a longer run of one target is FREEFORM_FUZZ_SECONDS=300 scripts/fuzz.sh T.
    export FREEFORM_FUZZ_SECONDS=${FREEFORM_FUZZ_SECONDS:-5}
    stage "fuzz ($FREEFORM_FUZZ_SECONDS s per target, $jobs at a time)"
    FREEFORM_FUZZ_NO_BUILD=1 scripts/fuzz.sh
  fi
fi
stage ""
echo "== all tests passed"
