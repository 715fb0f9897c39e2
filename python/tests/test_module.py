# The module's surface: the stub file lists exactly the public names the module has (so editors
# complete what exists), every public callable has a docstring, and the GIL is released in the long
# calls (a Python thread keeps running while deform works).
import ast
import pathlib

import numpy as np

import freeform as ff
from conftest import ticks_during

STUB = pathlib.Path(__file__).resolve().parents[1] / "freeform.pyi"


def stub_names():
    tree = ast.parse(STUB.read_text())
    classes = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            members = set()
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    members.add(item.name)
                elif isinstance(item, ast.AnnAssign):
                    members.add(item.target.id)
            classes[node.name] = members
    return classes


def test_stub_matches_the_module():
    stubs = stub_names()
    public = {n for n in dir(ff) if not n.startswith("_")}
    assert set(stubs) | {"ArrayLike", "F64"} >= {n for n in public if isinstance(getattr(ff, n), type)}
    for cls, members in stubs.items():
        assert hasattr(ff, cls), cls
        if cls == "Error":
            continue
        real = {n for n in dir(getattr(ff, cls)) if not n.startswith("_")}
        assert {m for m in members if not m.startswith("_")} == real, cls


def test_docstrings():
    for name in ["Lattice", "Binding", "BezierCurve", "Spline", "Patch", "Document", "MeshFile"]:
        cls = getattr(ff, name)
        assert cls.__doc__ and cls.__doc__.strip(), name
    for method in ["fit", "load", "save", "deform", "weights", "weights_matvec", "weights_rmatvec", "certify",
                   "bind", "direct_manipulation", "det_j", "deform_normals"]:
        assert getattr(ff.Lattice, method).__doc__, method


def test_gil_is_released_during_deform():
    points = np.random.default_rng(0).uniform(-1, 1, (2_000_000, 3))
    lat = ff.Lattice.fit(points)
    lat.control_points += 0.01

    def work():
        for _ in range(3):
            lat.deform(points, threads=1)

    # with the GIL held for the whole call the other thread could not tick at all
    assert ticks_during(work) >= 3
