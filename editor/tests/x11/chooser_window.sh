#!/bin/sh
# The desktop's file chooser in an interactive run (docs/editor.md, "Files"): the editor's real
# window under Xvfb, driven by xdotool, with a fake `zenity` first in PATH (a script that records
# its arguments and prints a path, as the real one does when a file is chosen):
#   1. Ctrl+O calls it (--file-selection and the editor's title in its arguments) and opens the
#      document it printed: three objects, no typed-path dialog;
#   2. a chooser that fails (exit 5: not a choice, not a cancel) falls back to the dialog where the
#      path is typed;
#   3. FREEFORM_NO_ZENITY=1 never calls it (the typed-path dialog at once);
#   4. a name typed there opens; the dialog opened again (and closed with Escape, and opened once
#      more): the name typed replaces the prefilled path.
# Usage: chooser_window.sh EDITOR WORKDIR. Exit 77 (skipped) without Xvfb, xdotool or python3.
set -u
EDITOR=$1
WORK=$2
command -v Xvfb >/dev/null 2>&1 || { echo "skip: no Xvfb"; exit 77; }
command -v xdotool >/dev/null 2>&1 || { echo "skip: no xdotool"; exit 77; }
command -v python3 >/dev/null 2>&1 || { echo "skip: no python3 to read the state"; exit 77; }
mkdir -p "$WORK/bin"
rm -f "$WORK"/state.json "$WORK"/zenity.log
. "$(dirname "$0")/xvfb.sh" # Xvfb on a free display, DISPLAY, the EXIT trap, wait_for

cat >"$WORK/doc.json" <<'DOC'
{"format": "freeform", "version": 1, "objects": [
 {"name": "c", "type": "bezier_curve", "points": [[-2, 0, 0], [-1, 0, 1.5], [1, 0, 1.5], [2, 0, 0]]}]}
DOC
cat >"$WORK/chosen.json" <<'DOC'
{"format": "freeform", "version": 1, "objects": [
 {"name": "a", "type": "bezier_curve", "points": [[0, 0, 0], [1, 0, 0]]},
 {"name": "b", "type": "bezier_curve", "points": [[0, 1, 0], [1, 1, 0]]},
 {"name": "d", "type": "bezier_curve", "points": [[0, 2, 0], [1, 2, 0]]}]}
DOC
# The fake: exit status from $WORK/zenity.status (0: chosen), the chosen path on stdout.
cat >"$WORK/bin/zenity" <<FAKE
#!/bin/sh
echo "\$@" >> "$WORK/zenity.log"
status=\$(cat "$WORK/zenity.status" 2>/dev/null || echo 0)
[ "\$status" = 0 ] && echo "$WORK/chosen.json"
exit \$status
FAKE
chmod +x "$WORK/bin/zenity"
PATH="$WORK/bin:$PATH"
export PATH
[ "$(command -v zenity)" = "$WORK/bin/zenity" ] || { echo "FAIL: the fake zenity is not first in PATH"; exit 1; }

WAIT_FOR_LOG="$WORK/zenity.log" # wait_for (xvfb.sh) prints it on failure
# start ENV...: the editor on doc.json with --state, its window focused.
start() {
    rm -f "$WORK/state.json"
    cd "$WORK" || exit 1
    env "$@" FREEFORM_AUTOSAVE_DIR="$WORK/autosave" ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" \
        "$EDITOR" "$WORK/doc.json" --size 1280x800 --state "$WORK/state.json" >"$WORK/editor.out" 2>"$WORK/editor.err" &
    EDITOR_PID=$!
    WID=$(timeout 20 xdotool search --sync --onlyvisible --name "freeform editor" | head -1)
    [ -n "$WID" ] || { echo "FAIL: no editor window"; cat "$WORK/editor.err"; exit 1; }
    xdotool windowfocus --sync "$WID" 2>/dev/null || xdotool windowfocus "$WID"
    wait_for "the first frame" "len(s['panels']) == 3 and s['objects'] == 1"
}
stop() {
    kill "$EDITOR_PID"; wait "$EDITOR_PID" 2>/dev/null
    EDITOR_PID=
}

# 1. The chooser answers with a file: it is opened.
echo 0 >"$WORK/zenity.status"
start FREEFORM_NO_ZENITY=0
xdotool key --clearmodifiers ctrl+o
wait_for "Ctrl+O opens the file the chooser printed" "s['objects'] == 3 and not s['path_dialog'] and s['error'] == ''"
grep -q -- "--file-selection" "$WORK/zenity.log" || { echo "FAIL: zenity was not asked for a file: $(cat "$WORK/zenity.log")"; exit 1; }
grep -q "freeform editor" "$WORK/zenity.log" || { echo "FAIL: no editor title in zenity's arguments: $(cat "$WORK/zenity.log")"; exit 1; }
stop

# 2. A chooser that fails: the typed path instead.
rm -f "$WORK/zenity.log"
echo 5 >"$WORK/zenity.status"
start FREEFORM_NO_ZENITY=0
xdotool key --clearmodifiers ctrl+o
wait_for "a failed chooser falls back to the typed path" "s['path_dialog'] and s['objects'] == 1"
[ -s "$WORK/zenity.log" ] || { echo "FAIL: the chooser was not tried"; exit 1; }
stop

# 3. FREEFORM_NO_ZENITY=1: never called.
rm -f "$WORK/zenity.log"
echo 0 >"$WORK/zenity.status"
start FREEFORM_NO_ZENITY=1
xdotool key --clearmodifiers ctrl+o
wait_for "FREEFORM_NO_ZENITY=1: the typed path" "s['path_dialog'] and s['objects'] == 1"
[ -e "$WORK/zenity.log" ] && { echo "FAIL: zenity was called with FREEFORM_NO_ZENITY=1"; exit 1; }

# 4. The typed path dialog opened again after a typed Open starts from its prefilled path,
#    selected: what is typed replaces it (issue 25: ImGui kept the field's edit state, the cursor
#    after the old name and no selection, and the typed name was appended to the old one). The
#    editor runs in $WORK, so the typed names are relative.
sleep 0.3
xdotool type --delay 20 "chosen.json"
xdotool key --clearmodifiers Return
wait_for "the first typed Open opens chosen.json" "s['objects'] == 3 and not s['path_dialog'] and s['error'] == ''"
xdotool key --clearmodifiers ctrl+o
wait_for "Ctrl+O opens the dialog" "s['path_dialog']"
xdotool key --clearmodifiers Escape
wait_for "Escape closes the dialog" "not s['path_dialog']"
printf '{"format": "freeform", "version": 1, "objects": [' >"$WORK/corrupt.json"
xdotool key --clearmodifiers ctrl+o
wait_for "Ctrl+O opens the dialog again" "s['path_dialog']"
sleep 0.3
xdotool type --delay 20 "corrupt.json"
xdotool key --clearmodifiers Return
wait_for "the second typed Open reads the name typed, not the old name with it appended" \
    "s['error'].startswith('corrupt.json: ') and s['objects'] == 3"
stop
echo "ok: the chooser's file opened, a failed chooser falls back to the typed path, FREEFORM_NO_ZENITY=1 never calls it," \
    "a second typed Open replaces the prefilled path"
