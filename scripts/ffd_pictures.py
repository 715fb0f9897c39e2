#!/usr/bin/env python3
"""Makes the before/after pictures of docs/ffd.md with the freeform tool and the editor.

    scripts/ffd_pictures.py [--build build] [--editor build/bin/freeform-editor] [--out docs/images]
                            [--work /tmp/ffd-pictures]

Steps (every one a command a user can run):
  1. the Utah teapot (data/teapot.bpt) tessellated into a triangle mesh: freeform tessellate;
  2. the rest lattice around it: freeform lattice --fit --degree 3,3,3;
  3. the lattice edited here: each horizontal layer k of control points (k = 0..3 along the
     lattice's u axis, which is z for the teapot) is twisted about the lattice's vertical centre line
     by TWIST * k/3 and scaled horizontally by PINCH[k] (a waist in the middle, the top widened);
  4. the mesh deformed: freeform ffd --report;
  5. the documents for the editor (the lattice object plus the mesh in the editor member, control
     nets shown, one camera for all) rendered headless under xvfb-run: ffd-teapot-before.png,
     ffd-teapot-after.png;
  6. the teapot's 32 Bézier patches (examples/data/demo-scene.json) deformed exactly through the same
     lattice (freeform ffd on a document: patches of degrees (27, 27)): ffd-teapot-exact.png.
"""

import argparse
import json
import math
import os
import subprocess
import sys

TWIST = math.radians(80)      # rotation of the top layer against the bottom one
PINCH = [1.0, 0.6, 0.8, 1.3]  # horizontal scale of layers k = 0..3


def run(cmd):
    print("+", " ".join(cmd), flush=True)
    out = subprocess.run(cmd, check=True, capture_output=True, text=True)
    return out.stdout


def bend(lattice):
    """Twist and pinch the layers of a fitted (axis-aligned) lattice object in place."""
    l, m, n = lattice["degree"]
    ox, oy, _ = lattice["origin"]
    cx = ox + 0.5 * lattice["axes"][0][0]
    cy = oy + 0.5 * lattice["axes"][1][1]
    for i in range(l + 1):
        for j in range(m + 1):
            for k in range(n + 1):
                p = lattice["points"][i * (m + 1) * (n + 1) + j * (n + 1) + k]
                a = TWIST * k / n
                s = PINCH[round(3 * k / n)]
                x, y = p[0] - cx, p[1] - cy
                p[0] = cx + s * (math.cos(a) * x - math.sin(a) * y)
                p[1] = cy + s * (math.sin(a) * x + math.cos(a) * y)


def document(objects, meshes=None, nets=True):
    editor = {"display": {"control_nets": nets, "control_points": nets}}
    if meshes:
        editor["meshes"] = [{"name": name, "path": path} for name, path in meshes]
    return {"format": "freeform", "version": 1, "objects": objects, "editor": editor}


def write(path, value):
    with open(path, "w") as f:
        json.dump(value, f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--editor", default=None)
    ap.add_argument("--out", default="docs/images")
    ap.add_argument("--work", default="/tmp/ffd-pictures")
    a = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    tool = os.path.join(a.build, "bin", "freeform")
    editor = a.editor or os.path.join(a.build, "bin", "freeform-editor")
    os.makedirs(a.work, exist_ok=True)
    w = lambda name: os.path.join(a.work, name)

    run([tool, "tessellate", os.path.join(root, "data", "teapot.bpt"), "-o", w("teapot.obj"), "--segments", "10",
         "--outward"])
    run([tool, "lattice", "--fit", w("teapot.obj"), "--degree", "3,3,3", "--margin", "0.05", "-o", w("rest.json")])
    rest = json.load(open(w("rest.json")))
    bent = json.loads(json.dumps(rest))
    bend(bent["objects"][0])
    write(w("bent.json"), bent)
    print(run([tool, "ffd", w("teapot.obj"), "--lattice", w("bent.json"), "-o", w("teapot-bent.obj"),
               "--report", w("report.json")]))

    write(w("before.json"), document(rest["objects"], [("teapot", w("teapot.obj"))]))
    write(w("after.json"), document(bent["objects"], [("teapot", w("teapot-bent.obj"))]))

    # The Bézier patches through the same lattice, exactly (the lattice object is skipped).
    scene = json.load(open(os.path.join(root, "examples", "data", "demo-scene.json")))
    patches = [o for o in scene["objects"] if o["type"] == "bezier_surface"]
    write(w("patches.json"), document(patches, nets=False))
    print(run([tool, "ffd", w("patches.json"), "--lattice", w("bent.json"), "-o", w("patches-bent.json")]))

    # One camera for every picture: the editor's iso view of the rest scene, a little closer.
    run([editor, w("before.json"), "--view", "iso", "--save", w("camera.json")])
    camera = json.load(open(w("camera.json")))["editor"]["camera"]
    camera["distance"] *= 0.8
    xvfb = ["xvfb-run", "-a", "-s", "-screen 0 1280x800x24"]
    shots = [("before.json", "ffd-teapot-before.png"), ("after.json", "ffd-teapot-after.png"),
             ("patches-bent.json", "ffd-teapot-exact.png")]
    for doc, png in shots:
        d = json.load(open(w(doc)))
        d.setdefault("editor", {})["camera"] = camera
        write(w(doc), d)
        run(xvfb + [editor, w(doc), "--screenshot", os.path.join(a.out, png), "--size", "960x600", "--no-ui"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
