#!/bin/sh
# Files dropped on the editor's real window through the X server's drag-and-drop protocol (issue
# 12, docs/editor.md "Documents"): Xvfb on a free display, the editor started on a document with
# --state, and xdnd_drop (xdnd_drop.cpp: an XDND source, as a file manager is) dropping on it:
#   1. a corrupt document: the error dialog is up naming the file, the document is unchanged (one
#      object, not modified); Escape closes it;
#   2. a mesh (data/meshes/sphere.obj): it is imported (two objects, modified, the status bar's
#      notice says which up axis the import used).
# Usage: drop_window.sh EDITOR XDND_DROP SOURCE_DIR WORKDIR. Exit 77 (skipped) without Xvfb or
# xdotool; < 60 s.
set -u
EDITOR=$1
DROP=$2
SOURCE=$3
WORK=$4
command -v Xvfb >/dev/null 2>&1 || { echo "skip: no Xvfb"; exit 77; }
command -v xdotool >/dev/null 2>&1 || { echo "skip: no xdotool"; exit 77; }
command -v python3 >/dev/null 2>&1 || { echo "skip: no python3 to read the state"; exit 77; }
mkdir -p "$WORK"
rm -f "$WORK"/state.json

. "$(dirname "$0")/xvfb.sh" # Xvfb on a free display, DISPLAY, the EXIT trap, wait_for

cat >"$WORK/doc.json" <<'DOC'
{"format": "freeform", "version": 1, "objects": [
 {"name": "c", "type": "bezier_curve", "points": [[-2, 0, 0], [-1, 0, 1.5], [1, 0, 1.5], [2, 0, 0]]}]}
DOC
printf '{"format": "freeform", "version": 1, "objects": [{"name": "c", "type": "bezier_curve", "points": [[0, 0], [1' >"$WORK/corrupt file.json"

FREEFORM_NO_ZENITY=1 FREEFORM_AUTOSAVE_DIR="$WORK/autosave" ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" \
    "$EDITOR" "$WORK/doc.json" --size 1280x800 --state "$WORK/state.json" >"$WORK/editor.out" 2>"$WORK/editor.err" &
EDITOR_PID=$!
WID=$(timeout 20 xdotool search --sync --onlyvisible --name "freeform editor" | head -1)
[ -n "$WID" ] || { echo "FAIL: no editor window"; cat "$WORK/editor.err"; exit 1; }

wait_for "the first frame" "len(s['panels']) == 3"
# (LeakSanitizer off for the dropping side too: Xlib keeps allocations to exit.)
export ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0"

# 1. A corrupt document dropped in the middle of the view (its name has a space: percent-encoded
#    in the uri-list, decoded by the window system's side).
"$DROP" "$WID" 640 400 "$WORK/corrupt file.json" || { echo "FAIL: the drop of the corrupt document"; exit 1; }
wait_for "the error of the dropped corrupt document" "'corrupt file.json' in s['error'] and s['objects'] == 1 and not s['modified']"
xdotool windowfocus --sync "$WID" 2>/dev/null || xdotool windowfocus "$WID"
xdotool key --clearmodifiers Escape
wait_for "Escape closes the error" "s['error'] == ''"

# 2. A mesh dropped: imported.
"$DROP" "$WID" 640 400 "$SOURCE/data/meshes/sphere.obj" || { echo "FAIL: the drop of the mesh"; exit 1; }
wait_for "the dropped mesh is imported" "s['objects'] == 2 and s['modified'] and s['error'] == ''"
echo "ok: a corrupt document and a mesh dropped through XDND"
exit 0
