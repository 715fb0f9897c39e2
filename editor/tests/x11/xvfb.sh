# Sourced by the real-window tests (sh): starts Xvfb at 1600 x 1000 on a display it picks itself
# (-displayfd: no race with X servers other tests start at the same time), installs the EXIT trap
# that stops it and the editor ($EDITOR_PID, when set), exports DISPLAY, and defines wait_for. Needs $WORK.
rm -f "$WORK/display"
Xvfb -displayfd 3 -screen 0 1600x1000x24 -nolisten tcp 3>"$WORK/display" >"$WORK/xvfb.log" 2>&1 &
XVFB=$!
EDITOR_PID=
cleanup() {
    [ -n "$EDITOR_PID" ] && kill "$EDITOR_PID" 2>/dev/null
    kill "$XVFB" 2>/dev/null
    wait 2>/dev/null
}
trap cleanup EXIT
i=0
until [ -s "$WORK/display" ] && grep -q '^[0-9][0-9]*$' "$WORK/display"; do
    i=$((i + 1)); [ $i -gt 200 ] && { echo "FAIL: Xvfb did not start"; cat "$WORK/xvfb.log"; exit 1; }
    kill -0 "$XVFB" 2>/dev/null || { echo "FAIL: Xvfb exited"; cat "$WORK/xvfb.log"; exit 1; }
    sleep 0.1
done
export DISPLAY=:$(cat "$WORK/display")

# wait_for WHAT PYTHON-EXPRESSION over s ($WORK/state.json, as the editor's --state writes it): up to
# 20 s; on failure prints WHAT, the state, the editor's stderr and $WAIT_FOR_LOG (when set), and exits 1.
wait_for() {
    python3 - "$WORK/state.json" "$2" <<'WAIT' && return 0
import json, sys, time
deadline = time.monotonic() + 20
while time.monotonic() < deadline:
    try:
        s = json.load(open(sys.argv[1]))
        if eval(sys.argv[2]):
            sys.exit(0)
    except (OSError, ValueError, KeyError, TypeError, IndexError):
        pass
    time.sleep(0.03)
sys.exit(1)
WAIT
    echo "FAIL: $1"; cat "$WORK/state.json" 2>/dev/null; cat "$WORK/editor.err"
    [ -n "${WAIT_FOR_LOG:-}" ] && cat "$WAIT_FOR_LOG" 2>/dev/null
    exit 1
}
