#!/usr/bin/env bash
# The fuzzing stage of CI (fuzz/README.md): builds the libFuzzer targets of fuzz/ with clang 14
# under AddressSanitizer + UndefinedBehaviorSanitizer in build-fuzz/, then runs each target for a
# fixed time on its seed corpus and dictionary. Any finding (crash, sanitizer report, leak,
# timeout, out-of-memory, violated property) fails the stage; the input is left in
# build-fuzz/findings/ and belongs in tests/regressions/ afterwards.
#
#   scripts/fuzz.sh              # CI: FREEFORM_FUZZ_SECONDS (default 10) per target
#   FREEFORM_FUZZ_SECONDS=120 scripts/fuzz.sh fuzz_mesh_ply   # a longer run of one target
#   FREEFORM_FUZZ_SEED=0 scripts/fuzz.sh   # a new random seed each run (CI uses seed 1, so a CI run
#                                          # is repeatable: the same mutations in the same order)
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${FREEFORM_FUZZ_SECONDS:-10}
jobs=$(nproc 2>/dev/null || echo 2)
targets=(fuzz_mesh_obj fuzz_mesh_ply fuzz_mesh_stl fuzz_mesh_off fuzz_mesh_gltf fuzz_mesh_glb
         fuzz_document fuzz_bpt fuzz_obj_freeform fuzz_cage fuzz_editor_replay fuzz_editor_settings
         fuzz_points)
if [ $# -gt 0 ]; then targets=("$@"); fi

if [ "${FREEFORM_FUZZ_NO_BUILD:-}" != "1" ]; then   # 1: run what build-fuzz/ already holds
echo "== fuzz build (clang, ASan + UBSan + libFuzzer)"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -gline-tables-only" \
  -DFREEFORM_SANITIZE=ON -DFREEFORM_BUILD_FUZZERS=ON -DFREEFORM_BUILD_TESTS=OFF -DFREEFORM_BUILD_EXAMPLES=OFF \
  -DFREEFORM_BUILD_BENCHMARKS=OFF -DFREEFORM_BUILD_EDITOR=OFF "${launcher[@]}" >/dev/null
cmake --build build-fuzz -j "$jobs" --target "${targets[@]}"
fi

mkdir -p build-fuzz/findings build-fuzz/logs
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
for t in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$t
  mkdir -p "$corpus"
  seeds=fuzz/corpus/${t#fuzz_}
  dict=fuzz/dict/${t#fuzz_}.dict
  args=(-max_total_time="$seconds" -seed="${FREEFORM_FUZZ_SEED:-1}" -rss_limit_mb=2048 -timeout=10 -max_len=65536 -print_final_stats=1
        -artifact_prefix=build-fuzz/findings/"$t"-)
  [ -f "$dict" ] && args+=(-dict="$dict")
  dirs=("$corpus")
  [ -d "$seeds" ] && dirs+=("$seeds")
  # Debian's assimp-testmodels (scripts/install-deps.sh) as more seeds: files from other tools.
  models=/usr/share/assimp/models
  case $t in
    fuzz_mesh_obj|fuzz_cage) [ -d $models/OBJ ] && dirs+=($models/OBJ) ;;
    fuzz_mesh_ply) [ -d $models/PLY ] && dirs+=($models/PLY) ;;
    fuzz_mesh_stl) [ -d $models/STL ] && dirs+=($models/STL) ;;
    fuzz_mesh_off) [ -d $models/OFF ] && dirs+=($models/OFF) ;;
    fuzz_mesh_gltf|fuzz_mesh_glb) [ -d $models/glTF2 ] && dirs+=($models/glTF2) ;;
  esac
  if build-fuzz/bin/"$t" "${args[@]}" "${dirs[@]}" >build-fuzz/logs/"$t".log 2>&1; then
    execs=$(grep -a -o 'stat::number_of_executed_units: *[0-9]*' build-fuzz/logs/"$t".log | grep -o '[0-9]*$' || true)
    rate=$(grep -a -o 'stat::average_exec_per_sec: *[0-9]*' build-fuzz/logs/"$t".log | grep -o '[0-9]*$' || true)
    edges=$(grep -a -o 'cov: [0-9]*' build-fuzz/logs/"$t".log | tail -1 | grep -o '[0-9]*' || true)
    echo "$t: ok, ${execs:-?} runs, ${rate:-?}/s, ${edges:-?} edges"
  else
    echo "$t: FINDING (build-fuzz/logs/$t.log, input in build-fuzz/findings/)"
    tail -40 build-fuzz/logs/"$t".log
    status=1
  fi
done
exit $status
