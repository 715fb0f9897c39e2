#!/usr/bin/env python3
"""Deform a mesh file with a lattice and write it back in its own format (docs/python.md).

    PYTHONPATH=build/python python3 examples/python/deform_mesh.py [MESH] [OUT]

Reads MESH (default data/meshes/sphere.obj) losslessly, fits a cubic lattice around it, lifts the
top layer of control points, deforms the file (positions, and normals by cof(J)) and writes OUT
(default: deformed-sphere.obj in freeform-examples/ of the system's temporary folder, never the
source tree), and the lattice next to it: everything else in the file stays as read.
"""
import pathlib
import sys
import tempfile

import freeform as ff

root = pathlib.Path(__file__).resolve().parents[2]
src = sys.argv[1] if len(sys.argv) > 1 else str(root / "data" / "meshes" / "sphere.obj")
dst = sys.argv[2] if len(sys.argv) > 2 else str(pathlib.Path(tempfile.gettempdir()) / "freeform-examples" /
                                                ("deformed-" + pathlib.Path(src).name))

mesh = ff.MeshFile.read(src)
lat = ff.Lattice.fit(mesh.positions, degree=(3, 3, 3), margin=0.05)
l, m, n = lat.degree
for i in range(l + 1):
    for j in range(m + 1):
        lat.control_points[lat.index(i, j, n)] += [0.0, 0.0, 0.4]  # lift the top layer
        lat.control_points[lat.index(i, j, n - 1)] *= [1.3, 1.3, 1.0]  # and widen the one below
print(lat)
print("certificate:", lat.certify()["verdict"])
report = mesh.deform(lat)
print("vertices:", report["vertices"], "min det J:", round(report["min_det_j"], 4), "folds:", report["fold_count"])
pathlib.Path(dst).parent.mkdir(parents=True, exist_ok=True)
mesh.write(dst)
lat.save(str(pathlib.Path(dst).with_suffix(".lattice.json")))
print("wrote", dst)
