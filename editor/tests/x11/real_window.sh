#!/bin/sh
# The editor's real window driven through the X server (issue 12): Xvfb on a free display, the
# editor started on a document with --state (it rewrites that file whenever its state changes),
# xdotool typing and clicking as a person would (XTEST: real key and button events, several per
# frame, Enter held across frames). One task end to end:
#   1. File > Open with Ctrl+O, the path of a corrupt document typed, Enter held for 0.3 s: the
#      error dialog is up with the file's error, and the document is unchanged;
#   2. Escape closes it; the wheel turned over the Properties panel (pointer moved there in the
#      same instant) leaves the camera alone; turned over the view it zooms;
#   3. the window resized to 900 x 600: every panel lies inside it, Properties against its right
#      edge; Ctrl+Q asks about the unsaved change (the zoom moved the document's camera).
# Usage: real_window.sh EDITOR WORKDIR. Exit 77 (skipped) without Xvfb or xdotool; < 60 s.
set -u
EDITOR=$1
WORK=$2
command -v Xvfb >/dev/null 2>&1 || { echo "skip: no Xvfb"; exit 77; }
command -v xdotool >/dev/null 2>&1 || { echo "skip: no xdotool"; exit 77; }
command -v python3 >/dev/null 2>&1 || { echo "skip: no python3 to read the state"; exit 77; }
mkdir -p "$WORK"
rm -f "$WORK"/state.json "$WORK"/state.json.part

# A free display number (no lock file, no socket).
n=91
while [ -e /tmp/.X$n-lock ] || [ -e /tmp/.X11-unix/X$n ]; do n=$((n + 1)); done
Xvfb :$n -screen 0 1600x1000x24 -nolisten tcp >"$WORK/xvfb.log" 2>&1 &
XVFB=$!
EDITOR_PID=
cleanup() {
    [ -n "$EDITOR_PID" ] && kill "$EDITOR_PID" 2>/dev/null
    kill "$XVFB" 2>/dev/null
    wait 2>/dev/null
}
trap cleanup EXIT
export DISPLAY=:$n
i=0
until xdotool getdisplaygeometry >/dev/null 2>&1; do
    i=$((i + 1)); [ $i -gt 100 ] && { echo "FAIL: Xvfb did not start"; cat "$WORK/xvfb.log"; exit 1; }
    sleep 0.1
done

cat >"$WORK/doc.json" <<'DOC'
{"format": "freeform", "version": 1, "objects": [
 {"name": "c", "type": "bezier_curve", "points": [[-2, 0, 0], [-1, 0, 1.5], [1, 0, 1.5], [2, 0, 0]]}]}
DOC
printf '{"format": "freeform", "version": 1, "objects": [{"name": "c", "type": "bezier_curve", "points": [[0, 0], [1' >"$WORK/corrupt.json"

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
# wait_for PYTHON-EXPRESSION over s (the state): up to 10 s.
wait_for() {
    i=0
    while [ $i -lt 100 ]; do
        if [ -f "$WORK/state.json" ] && python3 -c "import json,sys; s=json.load(open(sys.argv[1])); sys.exit(0 if ($2) else 1)" "$WORK/state.json" 2>/dev/null; then
            return 0
        fi
        i=$((i + 1)); sleep 0.1
    done
    echo "FAIL: $1"; cat "$WORK/state.json" 2>/dev/null; cat "$WORK/editor.err"; exit 1
}
wait_for "the first frame" "len(s['panels']) == 3"

# 1. Open a corrupt file, confirmed with Enter held across frames.
xdotool key --clearmodifiers ctrl+o
wait_for "the Open dialog" "s['path_dialog']"
xdotool key --clearmodifiers ctrl+a
xdotool type --delay 5 "$WORK/corrupt.json"
xdotool keydown Return; sleep 0.3; xdotool keyup Return
wait_for "the error of the corrupt file is shown after Enter" "'corrupt.json' in s['error'] and not s['path_dialog']"
sleep 0.3
wait_for "the error dialog stays up after Enter is released" "'corrupt.json' in s['error'] and s['objects'] == 1"

# 2. Escape closes it; the wheel over a panel, then over the view.
xdotool key Escape
wait_for "Escape closes the error dialog" "s['error'] == ''"
D0=$(state camera)
xdotool mousemove --window "$WID" 1100 200 click 4 click 4
sleep 0.5
D1=$(state camera)
[ "$D0" = "$D1" ] || { echo "FAIL: a scroll over the Properties panel moved the camera: $D0 -> $D1"; exit 1; }
xdotool mousemove --window "$WID" 640 400 click 4
wait_for "a scroll over the view zooms" "s['camera'] != $D0"

# 3. Resize to 900 x 600.
xdotool windowsize "$WID" 900 600
wait_for "the panels follow the window to 900 x 600" "s['window'] == [900, 600] and all(r[0] >= 0 and r[1] >= 0 and r[0] + r[2] <= 900 and r[1] + r[3] <= 600 and r[2] >= 150 for r in s['panels'].values()) and s['panels']['Properties'][0] + s['panels']['Properties'][2] == 892"

# Ctrl+Q: the zoom changed the document's camera, so the editor asks about unsaved changes.
xdotool mousemove --window "$WID" 450 300
xdotool key --clearmodifiers ctrl+q
wait_for "Ctrl+Q asks about the unsaved camera change" "s['unsaved_dialog'] and s['modified']"
kill "$EDITOR_PID"; wait "$EDITOR_PID" 2>/dev/null
EDITOR_PID=
echo "ok: open error with Enter held, scroll over a panel and over the view, resize to 900 x 600, quit asks"
