#!/usr/bin/env bash
# The fuzzing stage of CI (fuzz/README.md): the libFuzzer targets of fuzz/ live in build-asan/, the
# clang 14 build with AddressSanitizer + UndefinedBehaviorSanitizer that also holds the sanitizer
# tests (scripts/test.sh), so the library is compiled once for both. This script configures that
# folder (the same way scripts/test.sh does), builds the targets, then runs each target for a fixed
# time on its seed corpus and dictionary, as many at a time as there are cores. Any finding (crash,
# sanitizer report, leak, timeout, out-of-memory, violated property) fails the stage; the input is
# left in build-asan/fuzz/findings/ and belongs in tests/regressions/ afterwards.
#
#   scripts/fuzz.sh              # CI: FREEFORM_FUZZ_SECONDS (default 10) per target
#   FREEFORM_FUZZ_SECONDS=120 scripts/fuzz.sh fuzz_mesh_ply   # a longer run of one target
#   FREEFORM_FUZZ_SEED=0 scripts/fuzz.sh   # a new random seed each run (CI uses seed 1, so a CI run
#                                          # is repeatable: the same mutations in the same order)
#   FREEFORM_FUZZ_JOBS=1 scripts/fuzz.sh   # one target at a time
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${FREEFORM_FUZZ_SECONDS:-10}
jobs=$(nproc 2>/dev/null || echo 2)
targets=(fuzz_mesh_obj fuzz_mesh_ply fuzz_mesh_stl fuzz_mesh_off fuzz_mesh_gltf fuzz_mesh_glb
         fuzz_document fuzz_bpt fuzz_obj_freeform fuzz_cage fuzz_editor_replay fuzz_editor_settings
         fuzz_points)
if [ $# -gt 0 ]; then targets=("$@"); fi

if [ "${FREEFORM_FUZZ_NO_BUILD:-}" != "1" ]; then   # 1: run what build-asan/ already holds
  launcher=()
  if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
  generator=()
  if command -v ninja >/dev/null; then generator=(-G Ninja); fi
  want=Unix
  [ ${#generator[@]} -gt 0 ] && want=Ninja
  if [ -f build-asan/CMakeCache.txt ] && ! grep -q "^CMAKE_GENERATOR:INTERNAL=$want" build-asan/CMakeCache.txt; then
    rm -rf build-asan   # configured with another generator: start anew
  fi
  if [ -f build-asan/CMakeCache.txt ] && ! grep -q "^CMAKE_CXX_COMPILER:.*clang" build-asan/CMakeCache.txt; then
    rm -rf build-asan   # an older g++ sanitizer build: this folder is clang's now
  fi
  # The sanitizer build of scripts/test.sh: clang, -O1, ASan + UBSan, warnings as errors, the
  # library with libFuzzer's coverage instrumentation, no benchmarks, examples (no test runs them)
  # or render tests.
  CC=clang CXX=clang++ cmake -S . -B build-asan "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1" \
    -DFREEFORM_SANITIZE=ON -DFREEFORM_BUILD_FUZZERS=ON -DFREEFORM_WARNINGS_AS_ERRORS=ON \
    -DFREEFORM_BUILD_BENCHMARKS=OFF -DFREEFORM_BUILD_EXAMPLES=OFF -DFREEFORM_BUILD_RENDER_TESTS=OFF "${launcher[@]}" >/dev/null
  if [ "${FREEFORM_FUZZ_CONFIGURE_ONLY:-}" = "1" ]; then exit 0; fi
  echo "== fuzz build (build-asan: clang, ASan + UBSan + libFuzzer)"
  cmake --build build-asan -j "$jobs" --target "${targets[@]}"
fi

out=build-asan/fuzz
mkdir -p "$out/findings" "$out/logs"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# run TARGET: one target for its fixed time; its summary (or its finding) goes to $out/logs/TARGET.result.
run() {
  local t=$1
  local corpus=$out/corpus/$t
  mkdir -p "$corpus"
  local seeds=fuzz/corpus/${t#fuzz_}
  local dict=fuzz/dict/${t#fuzz_}.dict
  local args=(-max_total_time="$seconds" -seed="${FREEFORM_FUZZ_SEED:-1}" -rss_limit_mb=2048 -timeout=10 -max_len=65536
              -print_final_stats=1 -artifact_prefix="$out/findings/$t-")
  [ -f "$dict" ] && args+=(-dict="$dict")
  local dirs=("$corpus")
  [ -d "$seeds" ] && dirs+=("$seeds")
  # Debian's assimp-testmodels (scripts/install-deps.sh) as more seeds: files from other tools.
  local models=/usr/share/assimp/models
  case $t in
    fuzz_mesh_obj|fuzz_cage) [ -d $models/OBJ ] && dirs+=($models/OBJ) ;;
    fuzz_mesh_ply) [ -d $models/PLY ] && dirs+=($models/PLY) ;;
    fuzz_mesh_stl) [ -d $models/STL ] && dirs+=($models/STL) ;;
    fuzz_mesh_off) [ -d $models/OFF ] && dirs+=($models/OFF) ;;
    fuzz_mesh_gltf|fuzz_mesh_glb) [ -d $models/glTF2 ] && dirs+=($models/glTF2) ;;
  esac
  local log=$out/logs/$t.log
  if build-asan/bin/"$t" "${args[@]}" "${dirs[@]}" >"$log" 2>&1; then
    local execs rate edges
    execs=$(grep -a -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
    rate=$(grep -a -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
    edges=$(grep -a -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || true)
    echo "$t: ok, ${execs:-?} runs, ${rate:-?}/s, ${edges:-?} edges" >"$out/logs/$t.result"
  else
    { echo "$t: FINDING ($log, input in $out/findings/)"; tail -40 "$log"; } >"$out/logs/$t.result"
    return 1
  fi
}

# As many targets at a time as there are cores (FREEFORM_FUZZ_JOBS): each still runs its full time.
parallel=${FREEFORM_FUZZ_JOBS:-$jobs}
status=0
pids=()
names=()
finish_one() {   # waits for the oldest running target and prints its result
  local pid=${pids[0]} name=${names[0]}
  wait "$pid" || status=1
  cat "$out/logs/$name.result"
  pids=("${pids[@]:1}")
  names=("${names[@]:1}")
}
for t in "${targets[@]}"; do
  rm -f "$out/logs/$t.result"
  run "$t" &
  pids+=($!)
  names+=("$t")
  if [ ${#pids[@]} -ge "$parallel" ]; then finish_one; fi
done
while [ ${#pids[@]} -gt 0 ]; do finish_one; done
exit $status
