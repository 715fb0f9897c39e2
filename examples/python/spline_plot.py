#!/usr/bin/env python3
"""Fit a C2 cubic spline through points and plot it with matplotlib (docs/python.md).

    PYTHONPATH=build/python python3 examples/python/spline_plot.py [OUT.png]

Writes OUT.png (default: spline.png in freeform-examples/ of the system's temporary folder, never
the source tree). Without matplotlib (Debian: python3-matplotlib) the plot is skipped and the numbers
are printed.
"""
import pathlib
import sys
import tempfile

import numpy as np

import freeform as ff

points = np.array([[0, 0], [1, 2], [2.5, 2.2], [3.5, 0.5], [5, 1], [6, 3]], dtype=float)
spline = ff.Spline.interpolate(points, end="natural", parametrization="centripetal")
print(spline)
for joint in spline.continuity():
    print(f"joint {joint['joint']} at T = {joint['t']:.3f}: C{joint['C']} G{joint['G']}")
T = np.linspace(0, spline.domain_end, 400)
curve = spline.evaluate(T)
curvature_vectors = spline.derivatives(T, 2)[:, 2]

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib not installed: plot skipped; curve from", curve[0], "to", curve[-1])
    sys.exit(0)

out = sys.argv[1] if len(sys.argv) > 1 else str(pathlib.Path(tempfile.gettempdir()) / "freeform-examples" / "spline.png")
fig, ax = plt.subplots(figsize=(7, 4))
ax.plot(curve[:, 0], curve[:, 1], label="C2 spline")
ax.plot(spline.control_points[:, 0], spline.control_points[:, 1], ":o", ms=3, label="Bézier points")
ax.plot(points[:, 0], points[:, 1], "ks", label="data")
ax.set_aspect("equal")
ax.legend()
pathlib.Path(out).parent.mkdir(parents=True, exist_ok=True)
fig.savefig(out, dpi=120)
print("wrote", out)
