#!/usr/bin/env bash
# Sets up, builds and runs the main job: the README's first command.
# Until the editor lands this is a tour of the `freeform` command-line tool on the bundled example
# document examples/data/demo.json.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc 2>/dev/null || echo 2)" --target freeform-cli example_01_curve_basics

run() { echo; echo "\$ $*"; "$@"; }
run build/bin/freeform --help
run build/bin/freeform eval examples/data/demo.json --object arch --at 0.5 --derivatives 3
run build/bin/freeform eval examples/data/demo.json --object helix --at 0.25 --derivatives 1
run build/bin/example_01_curve_basics
echo
echo "\$ build/bin/freeform eval examples/data/demo.json --object arch --at 2   # outside [0, 1]"
build/bin/freeform eval examples/data/demo.json --object arch --at 2 || echo "(exit status $?)"
