# Sourced by the real-window tests (sh): starts Xvfb at 1600 x 1000 on a display it picks itself
# (-displayfd: no race with X servers other tests start at the same time), installs the EXIT trap
# that stops it and the editor ($EDITOR_PID, when set), and exports DISPLAY. Needs $WORK.
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
