#!/bin/sh
# The editor's real window driven through the X server (issue 12): Xvfb on a free display, the
# editor started on a document with --state (it rewrites that file whenever its state changes),
# xdotool typing and clicking as a person would (XTEST: real key and button events, several per
# frame, Enter held across frames). One task end to end:
#   1. File > Open with Ctrl+O, the path of a corrupt document typed, Enter held for 0.3 s: the
#      error dialog is up with the file's error, and the document is unchanged;
#   2. Escape closes it; Ctrl+I, sphere.gltf (a copy of data/meshes/sphere.gltf) typed, Enter and at once a click at the
#      window's centre: the sphere is imported (Y up) and selected (--state "selection"); L fits
#      a lattice, two of its points are dragged, Ctrl+Z undoes the second drag, Ctrl+S saves: the
#      saved lattice is at rest but for the first point dragged, the mesh kept with "up": "y";
#   3. the wheel turned over the Properties panel (pointer moved there in the same instant)
#      leaves the camera alone; turned over the view it zooms;
#   4. the window resized to 900 x 600: every panel lies inside it, Properties against its right
#      edge; Ctrl+Q asks about the unsaved change (the zoom moved the document's camera).
# Usage: real_window.sh EDITOR WORKDIR. Exit 77 (skipped) without Xvfb or xdotool; < 60 s (about
# 25-35 s on the shared, loaded machine).
set -u
EDITOR=$1
WORK=$2
command -v Xvfb >/dev/null 2>&1 || { echo "skip: no Xvfb"; exit 77; }
command -v xdotool >/dev/null 2>&1 || { echo "skip: no xdotool"; exit 77; }
command -v python3 >/dev/null 2>&1 || { echo "skip: no python3 to read the state"; exit 77; }
mkdir -p "$WORK"
rm -f "$WORK"/state.json "$WORK"/state.json.part

. "$(dirname "$0")/xvfb.sh" # Xvfb on a free display, DISPLAY, the EXIT trap, wait_for
xdotool getdisplaygeometry >/dev/null 2>&1 || { echo "FAIL: no X display $DISPLAY"; exit 1; }

cat >"$WORK/doc.json" <<'DOC'
{"format": "freeform", "version": 1, "objects": [
 {"name": "c", "type": "bezier_curve", "points": [[-2, 0, 0], [-1, 0, 1.5], [1, 0, 1.5], [2, 0, 0]]}]}
DOC
printf '{"format": "freeform", "version": 1, "objects": [{"name": "c", "type": "bezier_curve", "points": [[0, 0], [1' >"$WORK/corrupt.json"
# The typed paths are relative to $WORK, where the editor runs: xdotool cannot type every character
# a checkout's path may hold (it drops non-ASCII letters under Xvfb), and the test must not depend
# on where the checkout lies.
DATA=$(cd "$(dirname "$0")/../../.." && pwd)/data/meshes
cp "$DATA/sphere.gltf" "$DATA/sphere.bin" "$WORK/"
cd "$WORK" || exit 1

FREEFORM_NO_ZENITY=1 FREEFORM_AUTOSAVE_DIR="$WORK/autosave" ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" \
    "$EDITOR" "$WORK/doc.json" --size 1280x800 --state "$WORK/state.json" >"$WORK/editor.out" 2>"$WORK/editor.err" &
EDITOR_PID=$!
WID=$(timeout 20 xdotool search --sync --onlyvisible --name "freeform editor" | head -1)
[ -n "$WID" ] || { echo "FAIL: no editor window"; cat "$WORK/editor.err"; exit 1; }
xdotool windowfocus --sync "$WID" 2>/dev/null || xdotool windowfocus "$WID"

# state KEY: prints the value of a top-level field of the state file (JSON).
state() {
    python3 -c "import json,sys; print(json.dumps(json.load(open(sys.argv[1]))[sys.argv[2]]))" "$WORK/state.json" "$1" 2>/dev/null
}
# wait_for WHAT PYTHON-EXPRESSION: until the expression over s (the state) holds, up to 20 s of wall
# clock; one python process polls the file (starting python takes a second on a loaded machine).
wait_for "the first frame" "len(s['panels']) == 3"

# 1. Open a corrupt file, confirmed with Enter held across frames.
xdotool key --clearmodifiers ctrl+o
wait_for "the Open dialog" "s['path_dialog']"
xdotool key --clearmodifiers ctrl+a
xdotool type --delay 5 "corrupt.json"
xdotool keydown Return; sleep 0.3; xdotool keyup Return
wait_for "the error of the corrupt file is shown after Enter" "'corrupt.json' in s['error'] and not s['path_dialog']"
sleep 0.3
wait_for "the error dialog stays up after Enter is released" "'corrupt.json' in s['error'] and s['objects'] == 1"

# 2. Escape closes it. Then File > Import (Ctrl+I) of the glTF sphere (read Y up), a click on it at
#    the window's centre (the camera is fitted to the scene: the sphere's centre lies within a
#    few pixels of it, the curve c far above), L fits a lattice; two of its points are dragged,
#    Ctrl+Z undoes the second drag, Ctrl+S saves: the saved lattice has every point at rest
#    (X0 + (i/l) S + (j/m) T + (k/n) U, computed here from the saved origin and axes) but the
#    first one dragged, and the mesh is kept with "up": "y".
xdotool key Escape
wait_for "Escape closes the error dialog" "s['error'] == ''"
xdotool key --clearmodifiers ctrl+i
wait_for "the Import dialog" "s['path_dialog']"
xdotool type --delay 5 "sphere.gltf"
# Enter and, at once, the click: queued right behind the Enter that closes the dialog (as on a
# loaded machine, where frames lag behind the input), the click once fell on the closed dialog.
xdotool key Return mousemove --window "$WID" 640 400 click 1
# (The import's notice, "imported sphere.gltf as Y up", went with the click that followed it, a new
# action; the saved file's "up": "y" below shows the axis.)
wait_for "the glTF sphere is imported" "s['objects'] == 2 and not s['path_dialog'] and s['error'] == ''"
wait_for "a click on the imported sphere, right after the Enter that imported it, selects it" "s['selection'] is not None and s['selection']['item'] == 'sphere'"
xdotool key l
wait_for "L fits a lattice around the sphere and selects it" "s['objects'] == 3 and s['selection'] is not None and s['selection']['type'] == 'lattice'"
LATTICE=$(state selection | python3 -c "import json,sys; print(json.load(sys.stdin)['item'])")
# pick N: a lattice point in the open view (not under a panel), at least 16 px from every other
# point's place (so the click takes it and no other) and not the point numbered N; "k x y".
pick() {
    state selection | python3 -c "
import json, math, sys
s = json.load(sys.stdin); px = s['pixels']; skip = int(sys.argv[1])
for k, p in enumerate(px):
    if k == skip or p is None or not (330 < p[0] < 920 and 60 < p[1] < 740): continue
    if all(math.hypot(p[0] - q[0], p[1] - q[1]) >= 16 for i, q in enumerate(px) if i != k and q is not None):
        print(k, round(p[0]), round(p[1])); break
" "$1"
}
# drag K X Y: press on (X, Y), move 60 px right in steps, release; waits until point K has moved.
drag() {
    xdotool mousemove --window "$WID" "$2" "$3"
    wait_for "the pointer over point $1" "s['selection'] is not None"
    xdotool mousedown 1
    for dx in 10 20 30 40 50 60; do xdotool mousemove --window "$WID" $(($2 + dx)) "$3"; sleep 0.02; done
    xdotool mouseup 1
    wait_for "point $1 follows the drag" "s['selection']['points'] == [$1] and abs(s['selection']['pixels'][$1][0] - $2 - 60) < 2 and abs(s['selection']['pixels'][$1][1] - $3) < 2"
}
set -- $(pick -1)
[ $# -eq 3 ] || { echo "FAIL: no lattice point clear of the others in the view"; state selection; exit 1; }
A=$1; drag "$A" "$2" "$3"
set -- $(pick "$A")
[ $# -eq 3 ] || { echo "FAIL: no second lattice point clear of the others"; exit 1; }
B=$1; BX=$2; BY=$3; drag "$B" "$BX" "$BY"
xdotool key --clearmodifiers ctrl+z
wait_for "Ctrl+Z puts point $B back and leaves point $A dragged" "abs(s['selection']['pixels'][$B][0] - $BX) < 1 and abs(s['selection']['pixels'][$B][1] - $BY) < 1"
xdotool key --clearmodifiers ctrl+s
wait_for "Ctrl+S saves the document" "not s['modified']"
python3 - "$WORK/doc.json" "$LATTICE" "$A" <<'CHECK' || exit 1
import json, sys
doc = json.load(open(sys.argv[1])); name = sys.argv[2]; a = int(sys.argv[3])
lat = [o for o in doc["objects"] if o["name"] == name]
assert len(lat) == 1 and lat[0]["type"] == "lattice", f"FAIL: no lattice {name} in the saved document"
lat = lat[0]
l, m, n = lat["degree"]; x0 = lat["origin"]; S, T, U = lat["axes"]; pts = lat["points"]
assert len(pts) == (l + 1) * (m + 1) * (n + 1)
moved = []
for i in range(l + 1):
    for j in range(m + 1):
        for k in range(n + 1):
            rest = [x0[r] + i / l * S[r] + j / m * T[r] + k / n * U[r] for r in range(3)]
            p = pts[i * (m + 1) * (n + 1) + j * (n + 1) + k]
            if max(abs(p[r] - rest[r]) for r in range(3)) > 1e-9 * (1 + max(map(abs, rest))):
                moved.append(i * (m + 1) * (n + 1) + j * (n + 1) + k)
assert moved == [a], f"FAIL: the saved lattice has points {moved} away from rest; expected only [{a}]"
meshes = doc.get("editor", {}).get("meshes", [])
assert any(mm["name"] == "sphere" and mm.get("up") == "y" and mm["path"].endswith("sphere.gltf") for mm in meshes), \
    f"FAIL: the saved document lacks the sphere with up y: {meshes}"
CHECK

# 3. The wheel over a panel, then over the view.
D0=$(state camera)
xdotool mousemove --window "$WID" 1100 200 click 4 click 4
sleep 0.5
D1=$(state camera)
[ "$D0" = "$D1" ] || { echo "FAIL: a scroll over the Properties panel moved the camera: $D0 -> $D1"; exit 1; }
xdotool mousemove --window "$WID" 640 400 click 4
wait_for "a scroll over the view zooms" "s['camera'] != $D0"

# 4. Resize to 900 x 600.
xdotool windowsize "$WID" 900 600
wait_for "the panels follow the window to 900 x 600" "s['window'] == [900, 600] and all(r[0] >= 0 and r[1] >= 0 and r[0] + r[2] <= 900 and r[1] + r[3] <= 600 and r[2] >= 150 for r in s['panels'].values()) and s['panels']['Properties'][0] + s['panels']['Properties'][2] == 892"

# Ctrl+Q: the zoom changed the document's camera, so the editor asks about unsaved changes.
xdotool mousemove --window "$WID" 450 300
xdotool key --clearmodifiers ctrl+q
wait_for "Ctrl+Q asks about the unsaved camera change" "s['unsaved_dialog'] and s['modified']"
kill "$EDITOR_PID"; wait "$EDITOR_PID" 2>/dev/null
EDITOR_PID=
echo "ok: open error with Enter held, glTF sphere imported and clicked, lattice drags, undo, save, scroll over a panel and over the view, resize to 900 x 600, quit asks"
