#!/usr/bin/env bash
# The editor's frame while a lattice point is dragged over a real mesh, side by side with a frame
# at rest, phase by phase (docs/performance.md, "Editor frame time"). A real window on its own Xvfb
# (1600x1000, the editor at 1280x800, Mesa llvmpipe), driven by xdotool as a person drives it:
# click the mesh, L (fit a lattice of the panel's degrees, 3 x 3 x 3), then four rounds of two
# seconds at rest and a drag of the lattice's topmost corner point (below). The editor writes
# every frame's phases (--frame-log), and frame_log_summary.py prints their medians over the rest
# and the drag frames.
#
#   editor/benchmarks/drag_frame.sh [MESH]     # default: head.stl of Debian's occt-misc
#
# The pixel of the corner point (711, 149: the lattice's topmost corner) is where it lies for
# head.stl (64,215 vertices, 117,694 triangles; checked 2026-12-06). For another mesh, or when the
# summary says "no drag frames", look at a screenshot taken after L (`import -window root
# shot.png`) and edit it. Needs build/bin/freeform-editor, Xvfb and xdotool
# (scripts/install-deps.sh); head.stl: `apt-get install occt-misc`.
set -euo pipefail
cd "$(dirname "$0")/../.."
mesh=${1:-/usr/share/opencascade/data/stl/head.stl}
editor=${FREEFORM_EDITOR:-build/bin/freeform-editor}
if [ ! -f "$mesh" ]; then
  echo "error: $mesh: no such mesh (head.stl comes with Debian's occt-misc: apt-get install occt-misc)" >&2
  exit 1
fi
[ -x "$editor" ] || { echo "error: $editor: build the editor first (cmake --build build)" >&2; exit 1; }
log=$(mktemp --suffix=.tsv)
exec 3< <(Xvfb -displayfd 1 -screen 0 1600x1000x24 2>/dev/null)
xvfb_pid=$!
read -r display <&3
export DISPLAY=":$display"
cleanup() { kill "${editor_pid:-}" "$xvfb_pid" 2>/dev/null || true; }
trap cleanup EXIT
"$editor" "$mesh" --frame-log "$log" >/dev/null 2>&1 &
editor_pid=$!
window=""
for _ in $(seq 100); do
  window=$(xdotool search --name "freeform" 2>/dev/null | head -1 || true)
  [ -n "$window" ] && break
  sleep 0.2
done
[ -n "$window" ] || { echo "error: the editor's window did not appear" >&2; exit 1; }
sleep 3
eval "$(xdotool getwindowgeometry --shell "$window")"
xdotool mousemove $((X + 700)) $((Y + 420)) click 1   # select the mesh
sleep 1
xdotool key l                                          # fit a lattice
sleep 4
# Four rounds of two seconds at rest (the pointer over the corner point) and a drag of it over 40
# pointer moves, out by (40, -20) px and back again: rest and drag frames interleave, so a drift
# of the machine's speed shows in both.
x=711 y=149
for round in 1 2 3 4; do
  xdotool mousemove $((X + x)) $((Y + y))
  sleep 2
  step=1
  [ $((round % 2)) -eq 0 ] && step=-1
  # One xdotool process for the whole drag: one per move (40 process starts in 2 s) took the
  # two cores from the editor, and drag frames read 12-16 ms longer than frames at rest for it.
  moves=()
  for i in $(seq 1 40); do
    moves+=(mousemove $((X + x + step * i)) $((Y + y - step * i / 2)) sleep 0.05)
  done
  xdotool mousedown 1 "${moves[@]}" mouseup 1
  x=$((x + step * 40)) y=$((y - step * 20))
done
sleep 2
kill "$editor_pid"
wait "$editor_pid" 2>/dev/null || true
/usr/bin/python3 editor/benchmarks/frame_log_summary.py "$log"
echo "frame log: $log"
