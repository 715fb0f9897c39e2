# The module's surface: the stub file lists exactly the public names the module has (so editors
# complete what exists), every public callable has a docstring, and the GIL is released in the long
# calls (a Python thread keeps running while deform works).
import ast
import os
import pathlib
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

import freeform as ff
from conftest import ROOT, ticks_during

STUB = pathlib.Path(__file__).resolve().parents[1] / "freeform.pyi"


def stub_names():
    tree = ast.parse(STUB.read_text())
    classes = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
            members = set()
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    members.add(item.name)
                elif isinstance(item, ast.AnnAssign):
                    members.add(item.target.id)
            # A subclass (TrimmedSurface(Face)) has its bases' members too.
            for base in node.bases:
                if isinstance(base, ast.Name) and base.id in classes:
                    members |= classes[base.id]
            classes[node.name] = members
    return classes


def test_stub_matches_the_module():
    stubs = stub_names()
    public = {n for n in dir(ff) if not n.startswith("_")}
    assert set(stubs) >= {n for n in public if isinstance(getattr(ff, n), type)}
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


# ---------------------------------------------------------------- issue 26: the stubs as the module is

def split_top_level(text):
    """Splits a parameter list at the commas outside brackets and quotes."""
    parts, depth, quote, cur = [], 0, None, ""
    for ch in text:
        if quote:
            quote = None if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        cur += ch
    if cur.strip():
        parts.append(cur)
    return [p.strip() for p in parts]


def runtime_signatures(func):
    """Parameter names of each overload in a pybind11 docstring ("name(self: T, a: int = 0) -> R")."""
    name = func.__name__
    sigs = []
    for line in (func.__doc__ or "").splitlines():
        m = re.match(r"^(?:\d+\. )?" + re.escape(name) + r"\((.*)\) -> ", line)
        if m and m.group(1) != "*args, **kwargs":
            sigs.append([p.split(":")[0].split("=")[0].strip() for p in split_top_level(m.group(1))])
    return [[n for n in sig if n != "self"] for sig in sigs]


def stub_functions():
    tree = ast.parse(STUB.read_text())
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and not any(
                        isinstance(d, ast.Name) and d.id == "property" for d in item.decorator_list):
                    yield node.name, item
        elif isinstance(node, ast.FunctionDef):
            yield None, node


def test_stub_argument_names_are_the_module_s():
    # before: lat.index(i=1, j=2, k=0) type-checked and failed at run time (arg0..arg2)
    checked = 0
    for cls, fn in stub_functions():
        if fn.name in ("__getstate__", "__setstate__"):
            continue  # pickle's protocol, never called by keyword
        owner = getattr(ff, cls) if cls else ff
        runtime = getattr(owner, fn.name)
        a = fn.args
        names = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs if x.arg != "self"]
        sigs = runtime_signatures(runtime)
        assert sigs, f"{cls}.{fn.name}: no signature in its docstring"
        assert names in sigs, f"{cls}.{fn.name}: stub {names}, module {sigs}"
        assert not any(re.fullmatch(r"arg\d+", n) for sig in sigs for n in sig), f"{cls}.{fn.name}: {sigs}"
        checked += 1
    assert checked > 150
    lat = ff.Lattice((3, 2, 4), origin=[0, 0, 0], axes=np.eye(3))
    assert lat.index(i=1, j=2, k=0) == 25
    p = ff.Patch(np.zeros((2, 2, 3)))
    assert len(p.split_u(t=0.5)) == 2 and len(p.split_v(t=0.5)) == 2
    assert ff.BezierCurve([[0, 0], [1, 1]])(t=[0.5]).tolist() == [[0.5, 0.5]]
    assert ff.Document().__contains__(name="x") is False


def test_stubtest_passes(tmp_path):
    pytest.importorskip("mypy")
    stubs = tmp_path / "stubs"
    stubs.mkdir()
    shutil.copy(STUB, stubs / "freeform.pyi")
    config = tmp_path / "mypy.ini"
    config.write_text(f"[mypy]\ncache_dir = {tmp_path / 'mypy-cache'}\n")  # a fresh run takes about 4 s
    env = dict(os.environ, MYPYPATH=str(stubs), PYTHONPATH=os.path.dirname(ff.__file__))
    allowlist = pathlib.Path(__file__).with_name("stubtest_allowlist.txt")
    r = subprocess.run([sys.executable, "-m", "mypy.stubtest", "freeform", "--mypy-config-file", str(config),
                        "--allowlist", str(allowlist)],
                       capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stdout[-6000:] + r.stderr[-2000:]


def test_documents_example_of_the_docs_runs(tmp_path):
    # issue 26: the example named objects the files do not have and paths relative to the repository
    text = (ROOT / "docs" / "python.md").read_text()
    section = text.split("\n## Documents and meshes\n")[1].split("\n## ")[0]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    for old, new in [('pathlib.Path("path/to/freeform")', f"pathlib.Path({str(ROOT)!r})"),
                     ("pathlib.Path(tempfile.mkdtemp())", f"pathlib.Path({str(tmp_path)!r})")]:
        assert old in code
        code = code.replace(old, new)
    exec(compile(code, "docs/python.md", "exec"), {})
    assert (tmp_path / "deformed.json").exists() and (tmp_path / "sphere.ply").exists()
