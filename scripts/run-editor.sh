#!/usr/bin/env bash
# Builds the editor and opens it on the demo scene (the Utah teapot, a C2 spline and a curve).
# Without a display (no DISPLAY), it renders the demo scene off-screen under xvfb-run instead and
# writes the picture to build/demo-scene.png (or the path given as the first argument).
#
#   scripts/run-editor.sh               # window, or build/demo-scene.png when there is no display
#   scripts/run-editor.sh shot.png      # without a display: where the picture goes
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
# Ninja, as scripts/test.sh builds build/ (a folder configured before keeps its generator), and
# the same warnings-as-errors setting, so the test command later reuses what this one built.
generator=()
if [ ! -f build/CMakeCache.txt ] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DFREEFORM_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build build -j "$(nproc 2>/dev/null || echo 2)" --target freeform-editor

scene=examples/data/demo-scene.json
if [ -n "${DISPLAY:-}" ]; then
  exec build/bin/freeform-editor "$scene"
fi
out="${1:-build/demo-scene.png}"
echo "run-editor: there is no display (DISPLAY is not set), so the editor cannot open its window."
echo "run-editor: rendering $scene off-screen under xvfb-run instead -> $out"
xvfb-run -a -s "-screen 0 1280x800x24" build/bin/freeform-editor "$scene" --screenshot "$out" --size 1280x800
echo "run-editor: wrote $out (open it with any image viewer; on a machine with a display this script opens the editor)"
