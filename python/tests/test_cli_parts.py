# The command-line tool on parts, run as a person runs it (FREEFORM_CLI), in both kinds of build.
# The ctest test `python` runs this file with build/bin/freeform and build/python, which read and
# write STEP, IGES and BRep through Open CASCADE; `python_nocad` with build/bin/freeform-nocad and
# build/python-nocad, linked as a build without Open CASCADE (FREEFORM_BUILD_CAD=OFF) links them
# (python/CMakeLists.txt). Which kind is running: Part.formats of the module beside the tool.
import json
import pathlib
import subprocess

import numpy as np
import pytest

import freeform as ff
from conftest import ROOT, cli

PLATE = ROOT / "data" / "parts" / "plate.json"
SCREW = pathlib.Path("/usr/share/opencascade/data/step/screw.step")
WITH_CAD = ".step" in ff.Part.formats


def run(*args):
    return subprocess.run([cli(), *map(str, args)], capture_output=True, text=True)


def report(*args):
    r = run(*args)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    return json.loads(r.stdout)  # stdout holds the JSON and nothing else


def refused(r, path):
    """One error line naming the file and saying why, exit 1, nothing on stdout."""
    assert r.returncode == 1
    assert r.stdout == ""
    lines = r.stderr.splitlines()
    assert len(lines) == 1, r.stderr
    assert lines[0].startswith("error: ") and str(path) in lines[0]
    assert "built without Open CASCADE" in lines[0]


def obj_triangles(path):
    """(V, F) of an OBJ file of triangles, read here (not by the library)."""
    V, F = [], []
    for line in pathlib.Path(path).read_text().splitlines():
        if line.startswith("v "):
            V.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            F.append([int(x.split("/")[0]) - 1 for x in line.split()[1:]])
    return np.array(V), np.array(F)


def moved_lattice(tmp_path, offset, part=PLATE):
    """The degree-1 lattice the tool fits around the part, every point moved by offset."""
    rest = tmp_path / "rest.json"
    fitted = report("lattice", "--fit", part, "--degree", "1,1,1", "-o", rest)
    if part == PLATE:
        assert fitted["vertices"] == 10  # the plate's ten vertices (docs/cad.md, "Documents")
    doc = json.loads(rest.read_text())
    doc["objects"][0]["points"] = [list(np.add(p, offset)) for p in doc["objects"][0]["points"]]
    moved = tmp_path / "moved_lattice.json"
    moved.write_text(json.dumps(doc))
    return moved


def test_module_and_tool_are_of_one_kind_of_build():
    # The tool answers a CAD file as the module beside it says it would.
    r = run("info", SCREW)
    if WITH_CAD:
        assert r.returncode == 0, r.stderr
        assert json.loads(r.stdout)["faces"] == 10  # Open CASCADE's count (test_cad.py checks it against TopExp)
    else:
        refused(r, SCREW)


def test_a_documents_part_is_read_fitted_deformed_and_meshed_in_every_build(tmp_path):
    info = report("info", PLATE)
    assert (info["faces"], info["edges"], info["vertices"], info["closed"]) == (7, 15, 10, True)
    assert info["bounds"] == {"min": [0.0, 0.0, 0.0], "max": [40.0, 30.0, 10.0]}

    # A lattice fitted around the part and moved by (1, 2, 3) moves the part by (1, 2, 3).
    lattice = moved_lattice(tmp_path, [1.0, 2.0, 3.0])
    out = tmp_path / "moved.json"
    ffd = report("ffd", PLATE, "--lattice", lattice, "-o", out)
    assert [o["name"] for o in ffd["objects"]] == ["plate"]
    moved = report("info", out)
    assert (moved["faces"], moved["edges"], moved["vertices"], moved["closed"]) == (7, 15, 10, True)
    assert np.allclose(moved["bounds"]["min"], [1, 2, 3], rtol=0, atol=1e-12)
    assert np.allclose(moved["bounds"]["max"], [41, 32, 13], rtol=0, atol=1e-12)

    # Its mesh, from the OBJ file the tool wrote: every edge in two triangles, inside the box.
    mesh = tmp_path / "moved.obj"
    t = report("tessellate", out, "--object", "plate", "-o", mesh, "--tolerance", "0.1")
    assert t["watertight"] is True and t["certified"] is True and t["error_bound"] <= 0.1
    V, F = obj_triangles(mesh)
    assert (len(V), len(F)) == (t["vertices"], t["triangles"])
    edges = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    _, uses = np.unique(edges, axis=0, return_counts=True)
    assert set(uses.tolist()) == {2}
    assert np.all(V.min(axis=0) >= np.array([1, 2, 3]) - 1e-9) and np.all(V.max(axis=0) <= np.array([41, 32, 13]) + 1e-9)


@pytest.mark.parametrize("command", ["convert", "tessellate-step", "ffd-step", "info-step"])
def test_cad_files_go_through_open_cascade_or_are_refused_by_name(tmp_path, command):
    step = tmp_path / "plate.step"
    if command == "convert":
        r = run("convert", PLATE, "-o", step)
        written = step
    elif command == "tessellate-step":
        written = tmp_path / "screw.obj"
        r = run("tessellate", SCREW, "-o", written, "--tolerance", "0.1")
    elif command == "ffd-step":
        written = tmp_path / "screw_moved.step"
        lattice = moved_lattice(tmp_path, [0.0, 0.0, 1.0], SCREW if WITH_CAD else PLATE)
        r = run("ffd", SCREW, "--lattice", lattice, "-o", written)
    else:
        written = None
        r = run("info", step.with_name("absent.step"))
    if not WITH_CAD:
        named = {"convert": step, "info-step": step.with_name("absent.step")}.get(command, SCREW)
        refused(r, named)
        assert written is None or not written.exists()
        return
    if command == "info-step":  # a missing file: one error line naming it, as for any input
        assert r.returncode == 1 and r.stdout == "" and "absent.step" in r.stderr
        return
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert written.exists()
    if command == "convert":
        back = report("info", step)
        assert (back["faces"], back["edges"], back["vertices"], back["closed"]) == (7, 15, 10, True)
    elif command == "tessellate-step":
        assert out["watertight"] is True and out["certified"] is True
        assert len(obj_triangles(written)[1]) == out["triangles"]
    else:
        # A translation: affine, every face exact, the part read back with its counts.
        assert out["affine"] is True and out["exact_faces"] == out["faces"] == 10
        assert report("info", written)["faces"] == 10
