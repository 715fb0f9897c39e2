#!/bin/sh
# Ctrl+Q in the real window (docs/editor.md, the keyboard table and "Nothing is lost"): the editor
# under Xvfb, driven with xdotool (XTEST key and button events). With unsaved changes (the wheel
# over the view zooms: the document's camera changed) Ctrl+Q opens the unsaved-changes dialog and
# the editor stays; Escape (Cancel) closes it, the change still there and nothing written; Ctrl+S
# writes it (the saved camera distance is the zoomed one). Without unsaved changes now, Ctrl+Q
# quits: the process exits 0, its --state says `quit`, the file stays as saved.
# Usage: quit_window.sh EDITOR WORKDIR. Exit 77 (skipped) without Xvfb, xdotool or python3.
set -u
EDITOR=$1
WORK=$2
command -v Xvfb >/dev/null 2>&1 || { echo "skip: no Xvfb"; exit 77; }
command -v xdotool >/dev/null 2>&1 || { echo "skip: no xdotool"; exit 77; }
command -v python3 >/dev/null 2>&1 || { echo "skip: no python3 to read the state"; exit 77; }
mkdir -p "$WORK"
rm -f "$WORK"/state.json
. "$(dirname "$0")/xvfb.sh" # Xvfb on a free display, DISPLAY, the EXIT trap, wait_for

cat >"$WORK/original.json" <<'DOC'
{"format": "freeform", "version": 1, "objects": [
 {"name": "c", "type": "bezier_curve", "points": [[-2, 0, 0], [-1, 0, 1.5], [1, 0, 1.5], [2, 0, 0]]}]}
DOC
cp "$WORK/original.json" "$WORK/doc.json"

# The editor on doc.json with --state, its window focused.
start() {
    rm -f "$WORK/state.json"
    FREEFORM_NO_ZENITY=1 FREEFORM_AUTOSAVE_DIR="$WORK/autosave" ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" \
        "$EDITOR" "$WORK/doc.json" --size 1280x800 --state "$WORK/state.json" >"$WORK/editor.out" 2>"$WORK/editor.err" &
    EDITOR_PID=$!
    WID=$(timeout 20 xdotool search --sync --onlyvisible --name "freeform editor" | head -1)
    [ -n "$WID" ] || { echo "FAIL: no editor window"; cat "$WORK/editor.err"; exit 1; }
    xdotool windowfocus --sync "$WID" 2>/dev/null || xdotool windowfocus "$WID"
    wait_for "the first frame" "len(s['panels']) == 3 and s['objects'] == 1"
}
# exits WHAT: the editor process ends within 20 s with status 0.
exits() {
    i=0
    while kill -0 "$EDITOR_PID" 2>/dev/null; do
        i=$((i + 1)); [ $i -gt 200 ] && { echo "FAIL: $1: the editor is still running after 20 s"; exit 1; }
        sleep 0.1
    done
    wait "$EDITOR_PID"
    rc=$?
    EDITOR_PID=
    [ "$rc" = 0 ] || { echo "FAIL: $1: exit status $rc"; cat "$WORK/editor.err"; exit 1; }
}
# alive WHAT: the editor is still running half a second later.
alive() {
    sleep 0.5
    kill -0 "$EDITOR_PID" 2>/dev/null || { echo "FAIL: $1: the editor exited"; cat "$WORK/editor.err"; exit 1; }
}

# Unsaved changes: the dialog; Escape keeps the editor and the change; Ctrl+S writes it.
start
D0=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['camera']['distance'])" "$WORK/state.json")
xdotool mousemove --window "$WID" 640 400 click 4
wait_for "a scroll over the view zooms (an unsaved change)" "s['modified'] and s['camera']['distance'] != $D0"
xdotool key --clearmodifiers ctrl+q
wait_for "Ctrl+Q with unsaved changes opens the dialog" "s['unsaved_dialog'] and s['modified'] and not s['quit']"
alive "the unsaved-changes dialog is up"
xdotool key --clearmodifiers Escape
wait_for "Escape (Cancel) closes the dialog, the change kept" "not s['unsaved_dialog'] and s['modified'] and not s['quit']"
cmp -s "$WORK/original.json" "$WORK/doc.json" || { echo "FAIL: a cancelled quit rewrote the document's file"; exit 1; }
D1=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['camera']['distance'])" "$WORK/state.json")
xdotool key --clearmodifiers ctrl+s
wait_for "Ctrl+S saves the change" "not s['modified']"
python3 - "$WORK/doc.json" "$D1" <<'CHECK' || exit 1
import json, sys
doc = json.load(open(sys.argv[1]))
d = doc["editor"]["camera"]["distance"]
assert abs(d - float(sys.argv[2])) <= 1e-9 * abs(d), f"FAIL: the saved camera distance {d} is not the zoomed {sys.argv[2]}"
assert [o["name"] for o in doc["objects"]] == ["c"], f"FAIL: the saved objects {doc['objects']}"
CHECK
cp "$WORK/doc.json" "$WORK/saved.json"

# No unsaved changes now: Ctrl+Q quits, exit 0, the file as saved.
xdotool key --clearmodifiers ctrl+q
exits "Ctrl+Q without unsaved changes"
python3 -c "import json, sys; s = json.load(open(sys.argv[1])); sys.exit(0 if s['quit'] and not s['unsaved_dialog'] else 1)" "$WORK/state.json" ||
    { echo "FAIL: the state written at exit does not say quit"; cat "$WORK/state.json"; exit 1; }
cmp -s "$WORK/saved.json" "$WORK/doc.json" || { echo "FAIL: the quit rewrote the document's file"; exit 1; }
echo "ok: Ctrl+Q with unsaved changes opens the dialog, Escape keeps the editor and the change, Ctrl+S saves it, then Ctrl+Q quits (exit 0)"
