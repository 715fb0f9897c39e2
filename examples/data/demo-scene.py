#!/usr/bin/env python3
"""Writes examples/data/demo-scene.json, the editor's demo scene: the Utah teapot (data/teapot.bpt,
32 bicubic patches) as bezier_surface objects (oriented outwards), a closed C2 spline (de Boor points) around it and a
Bezier curve of steam above the spout.

    python3 examples/data/demo-scene.py      # from the repository root
"""
import json
import math
import os

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def read_bpt(path):
    numbers = open(path).read().split()
    pos = 0

    def take():
        nonlocal pos
        pos += 1
        return numbers[pos - 1]

    patches = []
    for _ in range(int(take())):
        m, n = int(take()), int(take())
        points = [[float(take()) for _ in range(3)] for _ in range((m + 1) * (n + 1))]
        patches.append((m, n, points))
    return patches


def number(x):
    """Shortest text that reads back to the same double, as the library writes numbers."""
    return int(x) if float(x).is_integer() else x


def transposed(m, n, points):
    """The same patch with u and v swapped: point (i, j) moves to (j, i), the normal f_v x f_u flips."""
    return n, m, [points[i * (n + 1) + j] for j in range(n + 1) for i in range(m + 1)]


# teapot.bpt's patches have f_u x f_v pointing into the teapot; the document stores them transposed
# so that their normals point out (the editor does the same when it imports a .bpt file).
objects = []
for i, patch in enumerate(read_bpt(os.path.join(root, "data", "teapot.bpt"))):
    m, n, points = transposed(*patch)
    grid = [[[number(c) for c in points[r * (n + 1) + k]] for k in range(n + 1)] for r in range(m + 1)]
    objects.append({"name": "teapot_%02d" % i, "type": "bezier_surface", "degree": [m, n], "points": grid})

ring = []
for k in range(8):
    a = 2 * math.pi * k / 8
    ring.append([number(round(4.2 * math.cos(a), 6)), number(round(4.2 * math.sin(a), 6)),
                 0.25 if k % 2 == 0 else 0.85])
objects.append({"name": "ring", "type": "deboor_spline", "degree": 3, "end": "closed", "points": ring})
objects.append({"name": "steam", "type": "bezier_curve",
                "points": [[3.35, 0, 2.5], [3.8, 0.4, 3.3], [2.9, -0.4, 3.7], [3.4, 0.2, 4.4]]})

document = {"format": "freeform", "version": 1, "objects": objects}
out = os.path.join(root, "examples", "data", "demo-scene.json")
# One object per block, one control point (or one row of a surface's grid) per line.
lines = ['{', '  "format": "freeform",', '  "version": 1,', '  "objects": [']
for k, o in enumerate(objects):
    head = {key: value for key, value in o.items() if key != "points"}
    text = json.dumps(head)[:-1] + ', "points": [\n'
    text += ",\n".join("      " + json.dumps(p) for p in o["points"])
    text += "]}" + ("," if k + 1 < len(objects) else "")
    lines.append("    " + text)
lines += ['  ]', '}']
with open(out, "w") as f:
    f.write("\n".join(lines) + "\n")
print("wrote", out, "with", len(objects), "objects")
