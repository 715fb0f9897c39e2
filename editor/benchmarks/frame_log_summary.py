#!/usr/bin/env python3
"""Summarises an editor frame log (freeform-editor --frame-log OUT.tsv; docs/performance.md,
"Editor frame time"): the median of every phase over the frames at rest (no drag, nothing changed)
and over the drag frames (a drag running and the scene changed), side by side.

    python3 editor/benchmarks/frame_log_summary.py OUT.tsv [--skip N]

--skip N leaves out the first N frames (the panels settling, the first upload).
"""
import argparse
import csv
import statistics
import sys

PHASES = ["input_ms", "ui_ms", "update_ms", "overlay_ms", "draw_ms", "gui_ms", "end_ms", "total_ms", "period_ms", "cpu_ms"]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("log")
    parser.add_argument("--skip", type=int, default=5)
    args = parser.parse_args()
    with open(args.log, newline="") as f:
        rows = [r for r in csv.DictReader(f, delimiter="\t") if int(r["frame"]) >= args.skip]
    groups = {
        "rest": [r for r in rows if r["dragging"] == "0" and r["changed"] == "0"],
        "drag": [r for r in rows if r["dragging"] == "1" and r["changed"] == "1"],
    }
    for name, group in groups.items():
        if not group:
            print(f"error: {args.log}: no {name} frames", file=sys.stderr)
            return 1
    print(f"{'phase (median ms)':<18} {'rest':>9} {'drag':>9} {'drag - rest':>12}")
    for phase in PHASES:
        rest = statistics.median(float(r[phase]) for r in groups["rest"])
        drag = statistics.median(float(r[phase]) for r in groups["drag"])
        print(f"{phase:<18} {rest:9.3f} {drag:9.3f} {drag - rest:12.3f}")
    print(f"{'frames':<18} {len(groups['rest']):9d} {len(groups['drag']):9d}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
